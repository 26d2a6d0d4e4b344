// A Menger sponge of three iterations in a cube of half size 1.
// Exercises: a for loop that breaks at a #define'd count (#ifndef giving the default), mod of
// negatives inside the loop (mod(p s, 2.0) - 1.0), sorting a vector's components with swizzle
// swaps (r.xy = r.yx), a function-like macro, ints.
#ifndef ITERATIONS
#define ITERATIONS 3
#endif
#define MAX3(v) max(max((v).x, (v).y), (v).z)

float map(vec3 p) {
  vec3 b = abs(p) - 1.0;
  float d = length(max(b, 0.0)) + min(MAX3(b), 0.0);
  float scale = 1.0;
  for (int i = 0; i < 8; i++) {
    if (i == ITERATIONS) break;
    vec3 a = mod(p * scale, 2.0) - 1.0;
    scale *= 3.0;
    vec3 r = abs(1.0 - 3.0 * abs(a));
    // The cross of three square bars is nearest along the middle one of r's components.
    if (r.x < r.y) r.xy = r.yx;
    if (r.y < r.z) r.yz = r.zy;
    if (r.x < r.y) r.xy = r.yx;
    d = max(d, (r.y - 1.0) / scale);
  }
  return d;
}

vec3 albedo(vec3 p) {
  vec3 a = abs(p);
  return mix(vec3(0.55, 0.3, 0.2), vec3(0.8, 0.75, 0.6), step(0.99, MAX3(a)));
}
