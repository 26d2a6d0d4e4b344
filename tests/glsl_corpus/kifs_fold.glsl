// A kaleidoscopic IFS: four iterations of a tetrahedral fold, a turn and a scale by 2, the turn
// growing with the time; an orbit trap in a global records how near the orbit came to the origin,
// for the colour.
// Exercises: a loop of swizzle-assigned folds (p.xy = -p.yx), a mat3 from Rodrigues' formula
// (mat3(1.0), a matrix of nine scalars, outerProduct, scalar x matrix) applied as matrix x
// vector, a global written inside map, pow, iTime, vec3 albedo(vec3 p) calling map.
float trap = 1e10;

// The turn by a about the unit axis k: c I + s [k]x + (1 - c) k k^T, [k]x column by column.
mat3 turn(vec3 k, float a) {
  float c = cos(a), s = sin(a);
  mat3 cross_k = mat3(0.0, k.z, -k.y, -k.z, 0.0, k.x, k.y, -k.x, 0.0);
  return c * mat3(1.0) + s * cross_k + (1.0 - c) * outerProduct(k, k);
}

float map(vec3 p) {
  mat3 r = turn(normalize(vec3(1.0, 0.5, 0.2)), 0.3 + 0.2 * iTime);
  const float scale = 2.0;
  for (int i = 0; i < 4; i++) {
    if (p.x + p.y < 0.0) p.xy = -p.yx;
    if (p.x + p.z < 0.0) p.xz = -p.zx;
    if (p.y + p.z < 0.0) p.yz = -p.zy;
    p = r * p;
    p = p * scale - vec3(scale - 1.0);
    trap = min(trap, dot(p, p));
  }
  return (length(p) - 2.0) * pow(scale, -4.0);
}

vec3 albedo(vec3 p) {
  map(p);
  float t = clamp(sqrt(trap) / 4.0, 0.0, 1.0);
  return mix(vec3(0.9, 0.5, 0.2), vec3(0.2, 0.4, 0.8), t);
}
