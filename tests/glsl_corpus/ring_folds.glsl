// Three stacked rings of eight boxes, turning with the time, hg_sdf style: helper functions fold
// the space in place through inout arguments and return the cell they folded it into, which the
// colour reads through out parameters.
// Exercises: inout parameters of float and vec2 passed swizzles and components (pR(p.xz, a),
// pMod1(p.y, s), pModPolar(p.xz, n)), out parameters, atan(y, x), mod, floor, a mat2 as matrix x
// vector, #if, iTime, vec3 albedo(vec3 p).
#define RING_COUNT 8.0
#define TAU 6.28318531
#define LEVEL_SPACING 0.75

void pR(inout vec2 p, float a) {
  p = mat2(cos(a), -sin(a), sin(a), cos(a)) * p;
}

// Folds p into [-size/2, size/2); returns the cell's index.
float pMod1(inout float p, float size) {
  float cell = floor(p / size + 0.5);
  p = mod(p + 0.5 * size, size) - 0.5 * size;
  return cell;
}

// Folds the plane's point into the sector of angle tau/n around +x; returns the sector's index.
float pModPolar(inout vec2 p, float n) {
  float sector = TAU / n;
  float a = atan(p.y, p.x) + 0.5 * sector;
  float index = floor(a / sector);
  a = mod(a, sector) - 0.5 * sector;
  p = length(p) * vec2(cos(a), sin(a));
  return index;
}

void fold(inout vec3 p, out float sector, out float level) {
  pR(p.xz, 0.3 * iTime);
  level = pMod1(p.y, LEVEL_SPACING);
  sector = pModPolar(p.xz, RING_COUNT);
}

float map(vec3 p) {
  vec3 q = p;
  float sector, level;
  fold(q, sector, level);
  vec3 d = abs(q - vec3(1.1, 0.0, 0.0)) - vec3(0.22, 0.2, 0.18);
  float box = length(max(d, 0.0)) + min(max(d.x, max(d.y, d.z)), 0.0);
#if 1
  float axle = length(p.xz) - 0.2;
  box = min(box, axle);
#endif
  return max(box, abs(p.y) - 1.2);
}

vec3 albedo(vec3 p) {
  // The axle has a colour of its own: the sector of a point on the axis is atan(0, 0)'s, which
  // GLSL leaves undefined (llvmpipe gives 3 pi / 4 for atan(-0, +0)).
  if (length(p.xz) < 0.3) return vec3(0.3);
  float sector, level;
  fold(p, sector, level);
  return vec3(0.5 + 0.5 * cos(sector), 0.4 + 0.15 * level, 0.6);
}
