/* A union of many operands, evaluated from data rather than from code of each: the grid of
 * host/prune/operand_grid.hpp, whose every cell lists, in the scene's order, only the operands
 * that can change the union inside it, so a step costs what is near and the program's size does
 * not grow with the scene. The generated code before this file defines GRID_COMBINE, GRID_BLEND
 * and GRID_ID_BLEND (the union's distance, material and id rules) and grid_operand_distance and
 * grid_operand_color (each operand's code by its shape, reading its numbers from its record).
 * The header's layout is in device_types.h. */

/* The grid's entry points are called, not inlined, where a work-item marches a packet: the program
 * calls the field from the march, the normals, shadows and occlusion, and inlining the lookup and
 * fold at every call made the first render of a 1,000-atom molecule 5.5 s with an empty PoCL cache,
 * against 3.7 s called, nearly all of it in PoCL's compiles (the kernel's time unchanged: a call
 * per step is nothing beside a fold over a cell's list; docs/performance.md). One pixel per
 * work-item relies on PoCL's vectoriser across work-items, which a call stops. */
#if LANES > 1
#define GRID_ENTRY static __attribute__((noinline))
#else
#define GRID_ENTRY SDF_INLINE
#endif

#define GRID_WORD(i) SCENE_DATA[i]
#define GRID_INT(i) as_int(SCENE_DATA[i])

/* The cell of each lane's point as a float index x + nx (y + ny z) (exact: at most 2^24 cells),
 * or -1 outside the grid. */
SDF_INLINE vfloat grid_cell_index(SceneValues values, vec3v p) {
  const float inverse_cell = GRID_WORD(CLMARCH_GRID_INVERSE_CELL);
  const vfloat x = floor((p.x - GRID_WORD(CLMARCH_GRID_ORIGIN)) * inverse_cell);
  const vfloat y = floor((p.y - GRID_WORD(CLMARCH_GRID_ORIGIN + 1)) * inverse_cell);
  const vfloat z = floor((p.z - GRID_WORD(CLMARCH_GRID_ORIGIN + 2)) * inverse_cell);
  const float nx = GRID_WORD(CLMARCH_GRID_DIMS), ny = GRID_WORD(CLMARCH_GRID_DIMS + 1),
              nz = GRID_WORD(CLMARCH_GRID_DIMS + 2);
  const vint inside = MASK(x >= 0.0f) & MASK(x < nx) & MASK(y >= 0.0f) & MASK(y < ny) & MASK(z >= 0.0f) & MASK(z < nz);
  return select((vfloat)(-1.0f), x + nx * (y + ny * z), inside);
}

/* Below the union's field outside the grid: every operand's bounding sphere lies outside_margin
 * inside the grid, so an operand is at least (distance to the grid + margin) / gain there, and
 * the smooth union undershoots its least operand by at most k. */
SDF_INLINE vfloat grid_outside_bound(SceneValues values, vec3v p) {
  const vec3v lower = v3((vfloat)(GRID_WORD(CLMARCH_GRID_ORIGIN)), (vfloat)(GRID_WORD(CLMARCH_GRID_ORIGIN + 1)),
                         (vfloat)(GRID_WORD(CLMARCH_GRID_ORIGIN + 2)));
  const vec3v upper = v3((vfloat)(GRID_WORD(CLMARCH_GRID_UPPER)), (vfloat)(GRID_WORD(CLMARCH_GRID_UPPER + 1)),
                         (vfloat)(GRID_WORD(CLMARCH_GRID_UPPER + 2)));
  const vec3v outside = v3_max0(
      v3(fmax(lower.x - p.x, p.x - upper.x), fmax(lower.y - p.y, p.y - upper.y), fmax(lower.z - p.z, p.z - upper.z)));
  return (v3_length(outside) + GRID_WORD(CLMARCH_GRID_OUTSIDE)) * GRID_WORD(CLMARCH_GRID_OUTSIDE + 1) -
         GRID_WORD(CLMARCH_GRID_OUTSIDE + 2);
}

/* The union folded over the operands cell lists, at every lane's point (the lanes outside the
 * cell are computed too and discarded by the caller). A cell's list is never empty. */
SDF_INLINE vfloat grid_cell_distance(SceneValues values, int cell, vec3v p) {
  const int cells = GRID_INT(CLMARCH_GRID_CELLS_AT), list = GRID_INT(CLMARCH_GRID_LIST_AT);
  const int first = GRID_INT(cells + cell), end = GRID_INT(cells + cell + 1);
  vfloat d = grid_operand_distance(values, GRID_INT(list + first), p);
  for (int i = first + 1; i < end; ++i) d = GRID_COMBINE(d, grid_operand_distance(values, GRID_INT(list + i), p));
  return d;
}

SDF_INLINE vfloat grid_cell_color(SceneValues values, int cell, vec3v p, vec3v* albedo, vec3v* surface, vec3v* emission,
                                  vfloat* id) {
  const int cells = GRID_INT(CLMARCH_GRID_CELLS_AT), list = GRID_INT(CLMARCH_GRID_LIST_AT);
  const int first = GRID_INT(cells + cell), end = GRID_INT(cells + cell + 1);
  vfloat d = grid_operand_color(values, GRID_INT(list + first), p, albedo, surface, emission, id);
  for (int i = first + 1; i < end; ++i) {
    vec3v next_albedo, next_surface, next_emission;
    vfloat next_id;
    const vfloat next =
        grid_operand_color(values, GRID_INT(list + i), p, &next_albedo, &next_surface, &next_emission, &next_id);
    *albedo = GRID_BLEND(*albedo, next_albedo, d, next);
    *surface = GRID_BLEND(*surface, next_surface, d, next);
    *emission = GRID_BLEND(*emission, next_emission, d, next);
    *id = GRID_ID_BLEND(*id, next_id, d, next);
    d = GRID_COMBINE(d, next);
  }
  return d;
}

/* The lanes of a packet mostly share a cell: each distinct cell among them is folded once for the
 * whole packet (one list, coherent vector code), its result kept for the lanes inside it. */
GRID_ENTRY vfloat grid_distance(SceneValues values, vec3v p) {
  const vfloat cell = grid_cell_index(values, p);
  vfloat d = grid_outside_bound(values, p);
  real cells[LANES];
  STORE_PRIVATE(cell, cells);
  for (int lane = 0; lane < LANES; ++lane) {
    const real c = cells[lane];
    if (c < 0) continue;
    d = select(d, grid_cell_distance(values, (int)c, p), MASK(cell == c));
    for (int other = lane; other < LANES; ++other) cells[other] = cells[other] == c ? -1 : cells[other];
  }
  return d;
}

GRID_ENTRY vfloat grid_distance_color(SceneValues values, vec3v p, vec3v* albedo, vec3v* surface, vec3v* emission,
                                      vfloat* id) {
  const vfloat cell = grid_cell_index(values, p);
  vfloat d = grid_outside_bound(values, p);
  *albedo = v3_splat(0.0f);
  *surface = v3_splat(0.0f);
  *emission = v3_splat(0.0f);
  *id = (vfloat)(-1.0f);
  real cells[LANES];
  STORE_PRIVATE(cell, cells);
  for (int lane = 0; lane < LANES; ++lane) {
    const real c = cells[lane];
    if (c < 0) continue;
    vec3v cell_albedo, cell_surface, cell_emission;
    vfloat cell_id;
    const vfloat cell_d = grid_cell_color(values, (int)c, p, &cell_albedo, &cell_surface, &cell_emission, &cell_id);
    const vint in_cell = MASK(cell == c);
    d = select(d, cell_d, in_cell);
    *albedo = v3_select(*albedo, cell_albedo, in_cell);
    *surface = v3_select(*surface, cell_surface, in_cell);
    *emission = v3_select(*emission, cell_emission, in_cell);
    *id = select(*id, cell_id, in_cell);
    for (int other = lane; other < LANES; ++other) cells[other] = cells[other] == c ? -1 : cells[other];
  }
  return d;
}
