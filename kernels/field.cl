/* The distance field as the march sees it, at a point in the frame map() is written in. Under the
 * mod tiling every sample wraps into the cell first; otherwise it is map() itself (under the cells
 * tiling the march keeps its points inside the current cell, and taps of normals and ambient
 * occlusion just past a wall still see that cell's geometry). */

/* p wrapped into the cell (the generated tiling_cell), floor-based like GLSL mod (OpenCL's fmod
 * truncates). */
#if defined(TILING_CELLS) || defined(TILING_MOD)
SDF_INLINE vec3v wrap_to_cell(SceneValues values, vec3v p) {
  const float4 cell = tiling_cell(values);
  return v3(p.x - cell.x * floor(p.x / cell.x), p.y - cell.y * floor(p.y / cell.y), p.z - cell.z * floor(p.z / cell.z));
}
#endif

SDF_INLINE vfloat field(SceneValues values, vec3v p) {
#if defined(TILING_MOD)
  return map(values, wrap_to_cell(values, p));
#else
  return map(values, p);
#endif
}

/* The field at a point off the march loops (a normal's taps, occlusion's samples): a stage
 * (lanes.cl), so that map() comes into the program once for all of them, not once per tap. */
SDF_STAGE vfloat field_tap(SceneValues values, vec3v p) { return field(values, p); }
