/* Surface normals from the distance field by finite differences with step h: central differences
 * (6 taps), Inigo Quilez's tetrahedral 4 taps (NORMAL_TETRAHEDRAL) or forward differences (4 taps,
 * NORMAL_FORWARD; first order like the tetrahedron, all taps on one side of p). The point is in
 * the frame map() is written in: under tiling the hit cell's own frame, so taps past a wall still
 * see that cell's geometry, and under the mod method taps wrap like the march did (field.cl). */

#ifdef NORMAL_TETRAHEDRAL
SDF_INLINE vec3v estimate_normal(SceneValues values, vec3v p, float h) {
  /* Taps at h * k.xyy, k.yyx, k.yxy, k.xxx with k = (1, -1). */
  vfloat a = field(values, v3(p.x + h, p.y - h, p.z - h));
  vfloat b = field(values, v3(p.x - h, p.y - h, p.z + h));
  vfloat c = field(values, v3(p.x - h, p.y + h, p.z - h));
  vfloat d = field(values, v3(p.x + h, p.y + h, p.z + h));
  return v3_normalize(v3(a - b - c + d, -a - b + c + d, -a + b - c + d));
}
#elif defined(NORMAL_FORWARD)
SDF_INLINE vec3v estimate_normal(SceneValues values, vec3v p, float h) {
  /* f(p + h e_i) - f(p); the shared tap f(p) is the fourth. */
  vfloat here = field(values, p);
  return v3_normalize(v3(field(values, v3(p.x + h, p.y, p.z)) - here, field(values, v3(p.x, p.y + h, p.z)) - here,
                         field(values, v3(p.x, p.y, p.z + h)) - here));
}
#else
SDF_INLINE vec3v estimate_normal(SceneValues values, vec3v p, float h) {
  vfloat dx = field(values, v3(p.x + h, p.y, p.z)) - field(values, v3(p.x - h, p.y, p.z));
  vfloat dy = field(values, v3(p.x, p.y + h, p.z)) - field(values, v3(p.x, p.y - h, p.z));
  vfloat dz = field(values, v3(p.x, p.y, p.z + h)) - field(values, v3(p.x, p.y, p.z - h));
  return v3_normalize(v3(dx, dy, dz));
}
#endif
