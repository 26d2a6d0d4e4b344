/* Colors as patterns of the point q in the frame of the node that sets them (host/scene/scene.hpp,
 * ColorPattern; the generated map_color calls these). A surface lying on a cell wall (a floor at
 * y = 0 under a checker) takes the cell on its outside: the march ends outside the surface, and
 * the hit point's coordinate keeps that sign (tests/shading_test.cpp, AFloorOnTheWallsTakesOneCell). */

/* Whether floor(v) is odd, for the integer-valued floor v. */
SDF_INLINE vint is_odd(vfloat v) { return MASK(v - 2.0f * floor(0.5f * v) != 0.0f); }

/* a where floor(x/size) + floor(y/size) + floor(z/size) is even, b where odd. */
SDF_INLINE vec3v pattern_checker(vec3v q, float size, vec3v a, vec3v b) {
  return v3_select(a, b, is_odd(floor(q.x / size) + floor(q.y / size) + floor(q.z / size)));
}

/* a where floor(coordinate/size) is even, b where odd. */
SDF_INLINE vec3v pattern_stripes(vfloat coordinate, float size, vec3v a, vec3v b) {
  return v3_select(a, b, is_odd(floor(coordinate / size)));
}

/* Whether coordinate lies within half_width of a multiple of size. */
SDF_INLINE vint near_grid_line(vfloat coordinate, float size, float half_width) {
  return MASK(fabs(coordinate - size * floor(coordinate / size + 0.5f)) < half_width);
}

/* GLSL's smoothstep, defined by its formula also where edge0 >= edge1 (OpenCL leaves it open). */
SDF_INLINE vfloat glsl_smoothstep(vfloat edge0, vfloat edge1, vfloat x) {
  const vfloat s = clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return s * s * (3.0f - 2.0f * s);
}
