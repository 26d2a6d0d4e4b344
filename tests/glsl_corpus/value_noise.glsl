// A sphere displaced by three octaves of 3D value noise drifting upwards with the time.
// Exercises: a hash-based value noise in Quilez's style (an integer hash of the lattice cell whose
// int multiplications wrap around, floor/fract, a smooth fade and a trilinear mix of the eight
// corners), a for loop of octaves with a mat3 rotation between them (matrix x vector), ints and
// ivec3, iTime, mix(vec3, vec3, float) in vec3 albedo(vec3 p).
// The hash is integer on purpose: the classic fract(sin(x) * 43758.5453) amplifies the last bits
// of sin, which differ between any two float implementations, so no implementation can match
// llvmpipe's within float rounding.

float hash(ivec3 c) {
  int n = c.x * 3 + c.y * 113 + c.z * 311;
  n = (n << 13) ^ n;
  n = n * (n * n * 15731 + 789221) + 1376312589;
  return float(n & 0x0fffffff) / float(0x0fffffff);
}

float noise(vec3 x) {
  vec3 f = fract(x);
  ivec3 c = ivec3(floor(x));
  vec3 u = f * f * (3.0 - 2.0 * f);
  return mix(mix(mix(hash(c + ivec3(0, 0, 0)), hash(c + ivec3(1, 0, 0)), u.x),
                 mix(hash(c + ivec3(0, 1, 0)), hash(c + ivec3(1, 1, 0)), u.x), u.y),
             mix(mix(hash(c + ivec3(0, 0, 1)), hash(c + ivec3(1, 0, 1)), u.x),
                 mix(hash(c + ivec3(0, 1, 1)), hash(c + ivec3(1, 1, 1)), u.x), u.y),
             u.z);
}

// An orthonormal turn between octaves, so that their lattices do not line up.
const mat3 octave_turn = mat3(0.00, 0.80, 0.60, -0.80, 0.36, -0.48, -0.60, -0.48, 0.64);

float fbm(vec3 p) {
  float sum = 0.0;
  float amplitude = 0.5;
  for (int i = 0; i < 3; i++) {
    sum += amplitude * noise(p);
    p = octave_turn * p * 2.02;
    amplitude *= 0.5;
  }
  return sum;
}

float map(vec3 p) {
  float sphere = length(p) - 1.2;
  float n = fbm(p * 2.0 + vec3(0.0, 0.3 * iTime, 0.0));
  // The noise's slope reaches a few units: 0.45 keeps the steps short of the surface.
  return 0.45 * (sphere + 0.3 * n);
}

vec3 albedo(vec3 p) {
  return mix(vec3(0.2, 0.35, 0.6), vec3(0.95, 0.9, 0.8), noise(p * 3.0));
}
