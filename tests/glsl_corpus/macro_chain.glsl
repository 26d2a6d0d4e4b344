// A chain of six links swinging with the time, every other link turned a quarter about the
// vertical, the first blended into a bar at the top with a smooth minimum.
// Exercises: function-like macros (nested, with arguments that are expressions), #ifdef/#if on a
// #define's value, a for loop with float accumulation, a mat2 from a macro applied as vector x
// matrix (p.xy *= ROT(a)), swizzle assignment, iTime.
#define SQ(x) ((x) * (x))
#define ROT(a) mat2(cos(a), sin(a), -sin(a), cos(a))
#define SMIN(a, b, k) (min(a, b) - SQ(max((k) - abs((a) - (b)), 0.0)) * 0.25 / (k))
#define LINKS 6
#define LINK_LENGTH 0.4

float link(vec3 p, float r) {
  p.y -= clamp(p.y, -LINK_LENGTH * 0.5, LINK_LENGTH * 0.5);
  return length(vec2(length(p.xy) - 0.2, p.z)) - r;
}

float map(vec3 p) {
  p.xy *= ROT(0.25 * sin(1.3 * iTime));
  vec3 q = p;
  q.y -= 1.2;
  float bar = length(vec2(length(q.yz), max(abs(q.x) - 0.8, 0.0))) - 0.08;
  float d = bar;
  float y = 1.2 - 0.2;
  for (int i = 0; i < LINKS; i++) {
    vec3 l = p;
    l.y -= y;
#ifdef LINKS
#if LINKS > 4
    if (i % 2 == 1) l.xz = l.zx;
#endif
#endif
    if (i == 0) {
      d = SMIN(d, link(l, 0.06), 0.08);
    } else {
      d = min(d, link(l, 0.06));
    }
    y -= LINK_LENGTH + 0.15;
  }
  return d;
}
