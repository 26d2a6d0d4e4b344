/* Surface normals from the distance field by finite differences with step h: central differences
 * (6 taps), Inigo Quilez's tetrahedral 4 taps (NORMAL_TETRAHEDRAL) or forward differences (4 taps,
 * NORMAL_FORWARD; first order like the tetrahedron, all taps on one side of p). The point is in
 * the frame map() is written in: under tiling the hit cell's own frame, so taps past a wall still
 * see that cell's geometry, and under the mod method taps wrap like the march did (field.cl). */

/* Each axis's differences are divided by the spacing its taps actually got: at large coordinates
 * p.x + h and p.x - h round to float, and their spacing differs from 2h by up to a unit of the
 * last place of p.x, differently on each axis, which turned the normal by up to 0.26 degrees at
 * |p| = 60 with h = 1e-4 (0.03 degrees with the spacing; tests/exact_depth_test.cpp). A spacing of
 * 0 (h below float's spacing at p) leaves that component 0, as before. */
SDF_INLINE vfloat tap_spacing(vfloat high, vfloat low) { return fmax(high - low, FLT_MIN); }

#ifdef NORMAL_TETRAHEDRAL
SDF_STAGE vec3v estimate_normal(SceneValues values, vec3v p, float h) {
  /* Taps at h * k.xyy, k.yyx, k.yxy, k.xxx with k = (1, -1). */
  const vec3v high = v3(p.x + h, p.y + h, p.z + h), low = v3(p.x - h, p.y - h, p.z - h);
  vfloat a = field_tap(values, v3(high.x, low.y, low.z));
  vfloat b = field_tap(values, v3(low.x, low.y, high.z));
  vfloat c = field_tap(values, v3(low.x, high.y, low.z));
  vfloat d = field_tap(values, v3(high.x, high.y, high.z));
  return v3_normalize(v3((a - b - c + d) / tap_spacing(high.x, low.x), (-a - b + c + d) / tap_spacing(high.y, low.y),
                         (-a + b - c + d) / tap_spacing(high.z, low.z)));
}
#elif defined(NORMAL_FORWARD)
SDF_STAGE vec3v estimate_normal(SceneValues values, vec3v p, float h) {
  /* f(p + h e_i) - f(p); the shared tap f(p) is the fourth. */
  const vec3v high = v3(p.x + h, p.y + h, p.z + h);
  vfloat here = field_tap(values, p);
  return v3_normalize(v3((field_tap(values, v3(high.x, p.y, p.z)) - here) / tap_spacing(high.x, p.x),
                         (field_tap(values, v3(p.x, high.y, p.z)) - here) / tap_spacing(high.y, p.y),
                         (field_tap(values, v3(p.x, p.y, high.z)) - here) / tap_spacing(high.z, p.z)));
}
#else
SDF_STAGE vec3v estimate_normal(SceneValues values, vec3v p, float h) {
  const vec3v high = v3(p.x + h, p.y + h, p.z + h), low = v3(p.x - h, p.y - h, p.z - h);
  vfloat dx = field_tap(values, v3(high.x, p.y, p.z)) - field_tap(values, v3(low.x, p.y, p.z));
  vfloat dy = field_tap(values, v3(p.x, high.y, p.z)) - field_tap(values, v3(p.x, low.y, p.z));
  vfloat dz = field_tap(values, v3(p.x, p.y, high.z)) - field_tap(values, v3(p.x, p.y, low.z));
  return v3_normalize(
      v3(dx / tap_spacing(high.x, low.x), dy / tap_spacing(high.y, low.y), dz / tap_spacing(high.z, low.z)));
}
#endif
