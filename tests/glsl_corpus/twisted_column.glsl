// A box column twisted about y, more with the height and turning with the time, on a round base.
// Exercises: a mat2 rotation applied as vector x matrix (q.xz *= rot(a)), swizzle assignment,
// iTime, #if/#else, vec3 albedo(vec3 p) with smoothstep and one-argument fract.
#define TWIST 0.6
#define ROUNDED 1

mat2 rot(float a) {
  float c = cos(a), s = sin(a);
  return mat2(c, s, -s, c);
}

float sdBox(vec3 p, vec3 b) {
  vec3 q = abs(p) - b;
  return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

float map(vec3 p) {
  vec3 q = p;
  q.xz *= rot(TWIST * q.y + 0.5 * iTime);
#if ROUNDED
  float column = sdBox(q, vec3(0.35, 1.2, 0.35)) - 0.08;
#else
  float column = sdBox(q, vec3(0.43, 1.28, 0.43));
#endif
  vec3 b = p;
  b.y += 1.3;
  float base = max(length(b.xz) - 0.9, abs(b.y) - 0.12);
  // The twist steepens the field by up to sqrt(1 + (TWIST r)^2) at the column's corners.
  return 0.85 * min(column, base);
}

vec3 albedo(vec3 p) {
  float band = smoothstep(0.4, 0.6, fract(p.y * 2.0));
  return mix(vec3(0.75, 0.3, 0.2), vec3(0.9, 0.85, 0.7), band);
}
