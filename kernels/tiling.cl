/* The unit-cell traversal of the tiling article, made exact (TILING_CELLS; the mod method needs
 * only field.cl's wrap). The ray lives in the current cell's frame (the camera's offset in its cell
 * comes from the host in double, so precision does not depend on the distance from the origin),
 * and when the wall ahead is nearer along the ray than the surface, the ray steps exactly to that
 * wall (a grid walk: wall distance divided by the direction component) and re-enters the next
 * cell at its opposite wall, crossing several axes at once at edges and corners. */

/* Distance along the ray from coordinate p to the wall it heads for; +inf for a zero direction
 * component (the ray never reaches that wall), never negative. inverse = 1 / dir: the walk takes
 * three of these a step, and a product costs a fraction of a division. */
SDF_INLINE vfloat wall_distance(vfloat p, vfloat dir, vfloat inverse, float cell) {
  const vfloat to_wall = select(-p, cell - p, MASK(dir > 0.0f));
  return select((vfloat)(INFINITY), fmax(to_wall * inverse, 0.0f), MASK(dir != 0.0f));
}

/* How far along the ray from p (in the cell's frame) the cell holds nothing: to where the ray
 * enters the sphere of bounds (MarchParams.cell_bounds), 0 inside it, +inf where the ray misses
 * it or has passed it. */
SDF_INLINE vfloat clear_reach(float4 bounds, vec3v p, vec3v dir) {
  vint meets = (vint)(-1);
  vfloat enter = (vfloat)(0.0f), leave = (vfloat)(INFINITY);
  clip_to_sphere(v3_sub(p, v3_from(bounds)), bounds.w, dir, &meets, &enter, &leave);
  return select((vfloat)(INFINITY), enter, meets);
}

/* The coordinate after a wall step: lanes crossing this axis re-enter the next cell at its
 * opposite wall; others stay inside [0, cell]. */
SDF_INLINE vfloat enter_next_cell(vfloat q, vfloat dir, vint crosses, float cell) {
  const vfloat opposite_wall = select((vfloat)(cell), (vfloat)(0.0f), MASK(dir > 0.0f));
  return select(clamp(q, 0.0f, cell), opposite_wall, crosses);
}

/* Marches origin + t * dir (origin in some cell's frame) for t from t_start, the starting point
 * wrapped into its cell; lanes stop at t_end. With the cell's bounds a step goes as far as the
 * larger of the distance and the stretch before the ray meets the bounds' sphere: a cell the ray
 * passes by takes one step, straight to its wall. */
SDF_STAGE MarchResult march_cells(vec3v origin, vec3v dir, vint live, vfloat t_start, vfloat t_end,
                                  MarchLimits limits) {
  const float4 cell = tiling_cell(limits.values);
  MarchResult m = march_result_init(t_start);
  /* The ray is entry + s * dir in the current cell's frame; m.t - s is its depth at entry. */
  vec3v entry = wrap_to_cell(limits.values, v3_add(origin, v3_scale(dir, t_start)));
  vfloat t_entry = t_start;
  vfloat s = (vfloat)(0.0f);
  vint active = live;
  const vec3v inverse_dir = v3(1.0f / dir.x, 1.0f / dir.y, 1.0f / dir.z);
  /* Over-relaxation as in march_plain, in the cell's coordinate s; a relaxed step ends at the wall
   * at the latest, and a wall step (exact) leaves nothing to undo. */
  vint relaxing = relaxation_mask(&limits);
  vfloat safe = (vfloat)(INFINITY);
  vfloat previous = (vfloat)(1e20f);
  for (int step = 0; step < limits.max_steps && LANE_ANY(active); ++step) {
    const vec3v p = v3_add(entry, v3_scale(dir, s));
    const vfloat wall_x = wall_distance(p.x, dir.x, inverse_dir.x, cell.x);
    const vfloat wall_y = wall_distance(p.y, dir.y, inverse_dir.y, cell.y);
    const vfloat wall_z = wall_distance(p.z, dir.z, inverse_dir.z, cell.z);
    const vfloat wall = fmin(wall_x, fmin(wall_y, wall_z));
    const vfloat reach = limits.cell_bounds.w > 0.0f ? clear_reach(limits.cell_bounds, p, dir) : (vfloat)(0.0f);
    /* When every lane passes its cell's bounding sphere by, each steps to its wall whatever the
     * distance, which is not evaluated then (+inf: outside the sphere it exceeds any hit threshold
     * and glow radius). A penumbra needs every sample, and a relaxed step may have crossed the
     * whole sphere: only the distance tells it to go back. */
    vfloat d = (vfloat)(INFINITY);
    if (limits.shadow_mode != CLMARCH_SHADOW_HARD || LANE_ANY(active & (MASK(reach < wall) | relaxing))) {
      d = map(limits.values, p);
    }
#if defined(RECORD_SAMPLES)
    record_samples(&limits, p, active, m.steps);
#endif
    /* The stretch ahead the step may take: the distance, or to the cell content's bounding sphere. */
    const vfloat clear = fmax(d, reach);
    m.steps += select((vfloat)(0.0f), (vfloat)(1.0f), active);
    m.t = t_entry + s;
    track_approach(&m, d, previous, active, &limits);
    previous = d;
    vint undo = (vint)(0);
    if (LANE_ANY(relaxing)) {
      undo = relaxing & MASK(d < s - safe);
      relaxing &= ~undo;
    }
    const vint arrived = active & ~undo & MASK(d < hit_threshold(&limits, m.t));
    m.hit |= arrived;
    active &= ~arrived;
    const vint to_wall = active & ~undo & MASK(wall <= clear);
    m.wall_steps += select((vfloat)(0.0f), (vfloat)(1.0f), to_wall);
    vfloat next = s + clear;
    if (LANE_ANY(relaxing | undo)) {
      /* Only the distance is relaxed: the stretch before the bounds' sphere is clear as it is. */
      next = select(select(next, s + fmin(fmax(d * limits.over_relaxation, reach), wall), relaxing), safe, undo);
      safe = select(s + clear, (vfloat)(INFINITY), to_wall);
    }
    s = select(s, next, active & ~to_wall);
    const vec3v at_wall = v3_add(p, v3_scale(dir, wall));
    const vec3v next_entry = v3(enter_next_cell(at_wall.x, dir.x, MASK(wall_x == wall), cell.x),
                                enter_next_cell(at_wall.y, dir.y, MASK(wall_y == wall), cell.y),
                                enter_next_cell(at_wall.z, dir.z, MASK(wall_z == wall), cell.z));
    entry = v3_select(entry, next_entry, to_wall);
    t_entry = select(t_entry, t_entry + s + wall, to_wall);
    s = select(s, (vfloat)(0.0f), to_wall);
    active &= MASK(t_entry + s < t_end);
    relaxing &= active;
  }
  m.t = t_entry + s;
  m.exhausted = active;
  m.local_point = v3_add(entry, v3_scale(dir, s));
  return m;
}

/* One march, whichever tiling the scene has: origin + t * dir, origin in map()'s frame. */
#define MARCH(origin, dir, live, t_start, t_end, limits) \
  march_cells((origin), (dir), (live), (t_start), (t_end), (limits))
