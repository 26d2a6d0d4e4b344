// A twisted rounded box with three beads on a rippled floor, its colour by height: the worked
// port of docs/porting-from-glsl.md, in Shadertoy style (rot, pR, a loop, a #define, iTime).
#define ITER 3
mat2 rot(float a) { float c = cos(a), s = sin(a); return mat2(c, s, -s, c); }
void pR(inout vec2 p, float a) { p = cos(a) * p + sin(a) * vec2(p.y, -p.x); }
float sdRoundBox(vec3 p, vec3 b, float r) {
  vec3 q = abs(p) - b;
  return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0) - r;
}
float map(vec3 p) {
  vec3 q = p - vec3(0.0, 1.0, 0.0);
  q.xz *= rot(0.4 * q.y + iTime);
  pR(q.xy, 0.3);
  float box = sdRoundBox(q, vec3(0.5, 0.8, 0.5), 0.1);
  float floor_ = p.y + 0.05 * sin(4.0 * p.x) * sin(4.0 * p.z);
  for (int i = 0; i < ITER; i++) box = min(box, length(q - vec3(0.6, 0.5 * float(i) - 0.5, 0.0)) - 0.2);
  return min(box, floor_);
}
vec3 albedo(vec3 p) { return mix(vec3(0.9, 0.3, 0.1), vec3(0.2, 0.5, 0.9), clamp(p.y, 0.0, 1.0)); }
