// A gear of twelve teeth around a hub, turning with the time: the teeth by polar repetition.
// Exercises: atan(y, x), mod of an angle that may be negative, an hg_sdf-style rotation
// pR(inout vec2 p, float a) called on a swizzle (pR(p.xz, a)), iTime, #define'd constants.
#define TEETH 12.0
#define PI 3.14159265

void pR(inout vec2 p, float a) {
  p = cos(a) * p + sin(a) * vec2(p.y, -p.x);
}

// The profile in the plane: a disc with teeth and a hole.
float gear_profile(vec2 q) {
  float sector = 2.0 * PI / TEETH;
  float a = mod(atan(q.y, q.x) + 0.5 * sector, sector) - 0.5 * sector;
  vec2 t = length(q) * vec2(cos(a), sin(a));
  float tooth = max(abs(t.y) - 0.12, t.x - 1.4);
  float disc = length(q) - 1.15;
  return max(min(disc, tooth), 0.45 - length(q));
}

float map(vec3 p) {
  pR(p.xz, 0.4 * iTime);
  float gear = max(gear_profile(p.xz), abs(p.y) - 0.15);
  float hub = max(abs(length(p.xz) - 0.45) - 0.08, abs(p.y) - 0.35);
  return min(gear, hub);
}
