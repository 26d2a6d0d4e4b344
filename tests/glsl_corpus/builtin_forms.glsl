// A rounded slab with a capsule handle and a row of slots, written with the vector-scalar forms of
// GLSL's built-ins, which OpenCL C spells differently or not at all.
// Exercises: min(vec, float), max(vec, float), clamp(vec, 0., 1.) and clamp(vec, vec, vec),
// mix(vec, vec, float) and mix(vec, vec, vec), step(float, vec), smoothstep(float, float, vec),
// mod(vec, float) of negatives and mod by a negative divisor, one-argument fract of negatives,
// sign, an exponential smooth minimum (exp, log), overloaded functions (an sdCapsule of vec2 and of
// vec3), #if, vec3 albedo(vec3 p).
#define SLOTS 1

float sdCapsule(vec3 p, vec3 a, vec3 b, float r) {
  vec3 pa = p - a, ba = b - a;
  float h = clamp(dot(pa, ba) / dot(ba, ba), 0.0, 1.0);
  return length(pa - ba * h) - r;
}

float sdCapsule(vec2 p, vec2 a, vec2 b, float r) {
  vec2 pa = p - a, ba = b - a;
  float h = clamp(dot(pa, ba) / dot(ba, ba), 0.0, 1.0);
  return length(pa - ba * h) - r;
}

// k = 8 keeps exp(-k d) a normal float (no flush to zero) as far as d = 10 from the surface.
float sminExp(float a, float b, float k) {
  return -log(exp(-k * a) + exp(-k * b)) / k;
}

float map(vec3 p) {
  vec3 size = vec3(1.4, 0.2, 0.9);
  vec3 q = abs(p) - size;
  // The box's distance: outside, to its nearest point clamp(p, -size, size).
  float slab = length(p - clamp(p, -size, size)) + min(max(q.x, max(q.y, q.z)), 0.0) - 0.05;
#if SLOTS
  // Slots every 0.5 along x: the cut's local x by mod of (possibly negative) x.
  vec3 s = p;
  s.x = mod(s.x, 0.5) - 0.25;
  float slot = sdCapsule(s.xz, vec2(0.0, -0.5), vec2(0.0, 0.5), 0.08);
  slab = max(slab, -max(slot, abs(p.x) - 1.1));
#endif
  float handle = sdCapsule(p, vec3(-0.6, 0.5, 0.0), vec3(0.6, 0.5, 0.0), 0.1);
  vec3 post = vec3(mod(p.x, -1.2) + 0.6, p.y - 0.35, p.z);
  handle = min(handle, max(length(post.xz) - 0.07, abs(post.y) - 0.15));
  handle = max(handle, abs(p.x) - 0.8);
  return sminExp(slab, handle, 8.0);
}

vec3 albedo(vec3 p) {
  vec3 checker = step(0.5, fract(p * 2.0));
  vec3 base = mix(vec3(0.2, 0.3, 0.5), vec3(0.9, 0.8, 0.6), checker.x * checker.z + (1.0 - checker.x) * (1.0 - checker.z));
  vec3 tint = smoothstep(-1.0, 1.0, p) * sign(p);
  vec3 mixed = mix(base, clamp(tint, 0.0, 1.0), vec3(0.2, 0.1, 0.3));
  return min(max(mixed, 0.05), 0.95);
}
