// A 4x4x4 block of cubes with some cells left empty, chosen by the bits of an integer hash of the
// cell.
// Exercises: ints and uints (ivec3 cells from floor, clamp of ivec3, int-to-uint conversion of
// negative ints, shifts, &, |, ^, uint multiplication that wraps around at 2^32), a #if choosing
// the hash, an early return, vec3 albedo(vec3 p) from the hash's bits.
#define UINT_HASH 1

#if UINT_HASH
uint hash(ivec3 c) {
  uint h = uint(c.x) * 73856093u ^ uint(c.y) * 19349663u ^ uint(c.z) * 83492791u;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  return h;
}
#else
uint hash(ivec3 c) { return uint((c.x * 7 + c.y * 13 + c.z * 29) & 255); }
#endif

ivec3 cell_of(vec3 p) { return clamp(ivec3(floor(p * 2.0)), ivec3(-2), ivec3(1)); }

float map(vec3 p) {
  ivec3 c = cell_of(p);
  vec3 q = p - (vec3(c) + 0.5) * 0.5;
  bool filled = (hash(c) & 3u) != 0u;
  vec3 d = abs(q) - vec3(0.18);
  float cube = length(max(d, 0.0)) + min(max(d.x, max(d.y, d.z)), 0.0) - 0.02;
  // Every other cube is past this cell's walls, and 0.05 beyond them, and inside the block.
  float walls = 0.25 - max(abs(q.x), max(abs(q.y), abs(q.z)));
  vec3 b = abs(p) - vec3(1.0);
  float block = length(max(b, 0.0)) + min(max(b.x, max(b.y, b.z)), 0.0);
  float others = max(walls + 0.05, block);
  if (!filled) return others;
  return min(cube, others);
}

vec3 albedo(vec3 p) {
  uint h = hash(cell_of(p));
  vec3 bits = vec3(float((h >> 4) & 1u), float((h >> 5) & 1u), float(((h >> 6) | (h >> 9)) & 1u));
  return 0.25 + 0.6 * bits;
}
