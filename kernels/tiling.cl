/* Infinite tiling of the scene, which is written in cell-local coordinates 0 <= p < TILING_CELL.
 * TILING_MOD: the cheap modulo of the sample point (breaks once objects exceed about a third of
 * the cell, and loses precision far from the origin). TILING_CELLS: the unit-cell traversal of the
 * tiling article, made exact: the ray lives in the current cell's frame (the camera's offset in
 * its cell comes from the host in double, so precision does not depend on the distance from the
 * origin), and when the wall ahead is nearer along the ray than the surface, the ray steps exactly
 * to that wall (a grid walk: wall distance divided by the direction component) and re-enters the
 * next cell at its opposite wall, crossing several axes at once at edges and corners. */

/* p wrapped into the cell, floor-based like GLSL mod (OpenCL's fmod truncates). */
SDF_INLINE vec3v wrap_to_cell(vec3v p) {
  const float4 cell = TILING_CELL;
  return v3(p.x - cell.x * floor(p.x / cell.x), p.y - cell.y * floor(p.y / cell.y), p.z - cell.z * floor(p.z / cell.z));
}

#if defined(TILING_MOD)
SDF_INLINE MarchResult march_mod(const MarchParams* params, vint live, vec3v origin, vec3v dir) {
  MarchResult m;
  m.t = (vfloat)(0.0f);
  m.steps = (vfloat)(0.0f);
  m.wall_steps = (vfloat)(0.0f);
  m.hit = (vint)(0);
  vint active = live;
  for (int step = 0; step < params->max_steps && LANE_ANY(active); ++step) {
    vfloat d = map(wrap_to_cell(v3_add(origin, v3_scale(dir, m.t))));
    m.steps += select((vfloat)(0.0f), (vfloat)(1.0f), active);
    vint arrived = active & MASK(d < params->epsilon);
    m.hit |= arrived;
    active &= ~arrived;
    m.t = select(m.t, m.t + d, active);
    active &= MASK(m.t < params->max_distance);
  }
  m.local_point = wrap_to_cell(v3_add(origin, v3_scale(dir, m.t)));
  return m;
}
#endif

#if defined(TILING_CELLS)
/* Distance along the ray from coordinate p to the wall it heads for; +inf for a zero direction
 * component (the ray never reaches that wall), never negative. */
SDF_INLINE vfloat wall_distance(vfloat p, vfloat dir, float cell) {
  const vfloat to_wall = select(-p, cell - p, MASK(dir > 0.0f));
  return select((vfloat)(INFINITY), fmax(to_wall / dir, 0.0f), MASK(dir != 0.0f));
}

/* The coordinate after a wall step: lanes crossing this axis re-enter the next cell at its
 * opposite wall; others stay inside [0, cell]. */
SDF_INLINE vfloat enter_next_cell(vfloat q, vfloat dir, vint crosses, float cell) {
  const vfloat opposite_wall = select((vfloat)(cell), (vfloat)(0.0f), MASK(dir > 0.0f));
  return select(clamp(q, 0.0f, cell), opposite_wall, crosses);
}

SDF_INLINE MarchResult march_cells(const MarchParams* params, vint live, vec3v dir) {
  const float4 cell = TILING_CELL;
  MarchResult m;
  m.steps = (vfloat)(0.0f);
  m.wall_steps = (vfloat)(0.0f);
  m.hit = (vint)(0);
  /* The ray is entry + s * dir in the current cell's frame; t_entry is its depth at entry. */
  vec3v entry = v3_from(params->origin_in_cell);
  vfloat t_entry = (vfloat)(0.0f);
  vfloat s = (vfloat)(0.0f);
  vint active = live;
  for (int step = 0; step < params->max_steps && LANE_ANY(active); ++step) {
    const vec3v p = v3_add(entry, v3_scale(dir, s));
    const vfloat d = map(p);
    const vfloat wall_x = wall_distance(p.x, dir.x, cell.x);
    const vfloat wall_y = wall_distance(p.y, dir.y, cell.y);
    const vfloat wall_z = wall_distance(p.z, dir.z, cell.z);
    const vfloat wall = fmin(wall_x, fmin(wall_y, wall_z));
    m.steps += select((vfloat)(0.0f), (vfloat)(1.0f), active);
    const vint arrived = active & MASK(d < params->epsilon);
    m.hit |= arrived;
    active &= ~arrived;
    const vint to_wall = active & MASK(wall <= d);
    m.wall_steps += select((vfloat)(0.0f), (vfloat)(1.0f), to_wall);
    s = select(s, s + d, active & ~to_wall);
    const vec3v at_wall = v3_add(p, v3_scale(dir, wall));
    const vec3v next_entry = v3(enter_next_cell(at_wall.x, dir.x, MASK(wall_x == wall), cell.x),
                                enter_next_cell(at_wall.y, dir.y, MASK(wall_y == wall), cell.y),
                                enter_next_cell(at_wall.z, dir.z, MASK(wall_z == wall), cell.z));
    entry = v3_select(entry, next_entry, to_wall);
    t_entry = select(t_entry, t_entry + s + wall, to_wall);
    s = select(s, (vfloat)(0.0f), to_wall);
    active &= MASK(t_entry + s < params->max_distance);
  }
  m.t = t_entry + s;
  m.local_point = v3_add(entry, v3_scale(dir, s));
  return m;
}
#endif
