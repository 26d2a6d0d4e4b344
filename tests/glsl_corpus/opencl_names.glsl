// A lantern: a box frame around a sphere on a plinth, written with names that OpenCL C takes for
// its keywords, types, built-ins and macros, and names of clmarch's own kernels and generated code.
// Exercises: variables, parameters, functions and a struct named local, global, constant, kernel,
// private, select, clamp (a variable hiding the built-in in its scope), float2, uchar, size_t,
// read_only, sampler_t, image2d_t, get_global_id, fmod, mad, native_sqrt, as_float, convert_int,
// INFINITY, M_PI_F, MAXFLOAT, NULL, real, real3, vec3v, sd_box, op_union, map_color; a struct's
// members; a mat2 as matrix x vector.
struct float2 {
  float global;
  float local;
};

float INFINITY = 1e9;

// GLSL's mod, under the name of C's truncating one: a translation that calls C's fmod for it
// (or defines a helper of that name) breaks.
float fmod(float a, float b) { return a - b * floor(a / b); }

float mad(float a, float b, float c) { return a * b - c; }

float sd_box(vec3 p, vec3 size_t) {
  vec3 local = abs(p) - size_t;
  float global = length(max(local, 0.0));
  float constant = min(max(local.x, max(local.y, local.z)), 0.0);
  return global + constant;
}

float op_union(float kernel, float private) { return min(kernel, private); }

float select(float a, float b, bool c) { return c ? a : b; }

// The distance to the octant v <= 0 (a box's corner at the origin).
float image2d_t(vec3 v) { return length(max(v, 0.0)) + min(max(v.x, max(v.y, v.z)), 0.0); }

// Quilez's box frame: the edges of a box of half size b, e thick.
float frame(vec3 p, vec3 b, float e) {
  vec3 read_only = abs(p) - b;
  vec3 q = abs(read_only + e) - e;
  float2 sampler_t = float2(image2d_t(vec3(read_only.x, q.y, q.z)), image2d_t(vec3(q.x, read_only.y, q.z)));
  float NULL = image2d_t(vec3(q.x, q.y, read_only.z));
  return min(min(sampler_t.global, sampler_t.local), NULL);
}

float map_color(vec3 p) { return p.y; }

float map(vec3 p) {
  float MAXFLOAT = INFINITY;
  vec3 real3 = p - vec3(0.0, 0.2, 0.0);
  float real = frame(real3, vec3(0.6, 0.8, 0.6), 0.06) - 0.01;
  float vec3v = length(real3) - 0.45;
  float native_sqrt = select(vec3v, real, vec3v < real);
  float get_global_id = sd_box(p + vec3(0.0, 0.75, 0.0), vec3(0.8, 0.12, 0.8));
  mat2 convert_int = mat2(0.8, 0.6, -0.6, 0.8);
  vec2 as_float = convert_int * p.xz;
  float plinth = max(get_global_id, (abs(as_float.x) + abs(as_float.y) - 1.1) * 0.70710678);
  float clamp = op_union(native_sqrt, plinth);
  return min(clamp, MAXFLOAT);
}

vec3 albedo(vec3 p) {
  float clamp = 0.5;
  vec3 constant = vec3(map_color(p), 0.4, 0.6);
  int uchar = int(fmod(floor(p.y * 4.0), 3.0));
  float M_PI_F = uchar == 1 ? 0.2 : 0.0;
  return clamp + M_PI_F + 0.3 * sin(constant * 3.0 + vec3(mad(2.0, 1.5, 1.0), 0.0, 1.0));
}
