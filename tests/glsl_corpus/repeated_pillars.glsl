// A 5x5 block of capped pillars: domain repetition with mod, each pillar's height from its integer
// cell, the block cut out of the infinite repetition by a box.
// Exercises: mod of negative coordinates (mod(x, s) = x - s floor(x / s), never C's fmod), ints
// from floor (ivec2 cells, & of negative ints), ternaries, #if/#elif/#else, swizzle assignment,
// vec3 albedo(vec3 p) by the cell's parity.
#define SPACING 1.0
#define SHAPE 2  // 1: boxes, 2: rounded cylinders, else spheres

float pillar(vec3 q, float h) {
#if SHAPE == 1
  vec3 d = abs(q) - vec3(0.3, h, 0.3);
  return length(max(d, 0.0)) + min(max(d.x, max(d.y, d.z)), 0.0);
#elif SHAPE == 2
  vec2 d = vec2(length(q.xz) - 0.25, abs(q.y) - h);
  return min(max(d.x, d.y), 0.0) + length(max(d, 0.0)) - 0.05;
#else
  return length(q) - h;
#endif
}

ivec2 cell_of(vec3 p) { return ivec2(floor(p.xz / SPACING + 0.5)); }

float map(vec3 p) {
  ivec2 cell = cell_of(p);
  float h = ((cell.x + cell.y) & 1) == 0 ? 0.9 : 0.6;
  vec3 q = p;
  q.xz = mod(q.xz + 0.5 * SPACING, SPACING) - 0.5 * SPACING;
  q.y += 1.0 - h;
  float own = pillar(q, h);
  // The pillars of the other cells, of other heights, are at least this far: past this cell's
  // side walls and the 0.2 gap between a pillar and its cell's side.
  float others = 0.5 * SPACING - max(abs(q.x), abs(q.z)) + 0.2;
  vec3 block = abs(p) - vec3(2.5, 1.0, 2.5);
  float inside_block = max(block.x, max(block.y, block.z));
  return max(min(own, others), inside_block);
}

vec3 albedo(vec3 p) {
  ivec2 cell = cell_of(p);
  return ((cell.x ^ cell.y) & 1) == 0 ? vec3(0.85, 0.8, 0.7) : vec3(0.3, 0.45, 0.7);
}
