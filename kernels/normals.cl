/* Surface normals from the distance field by finite differences with step h: central differences
 * (6 taps) or Inigo Quilez's tetrahedral 4 taps (NORMAL_TETRAHEDRAL). */

#ifdef NORMAL_TETRAHEDRAL
SDF_INLINE vec3v estimate_normal(vec3v p, float h) {
  /* Taps at h * k.xyy, k.yyx, k.yxy, k.xxx with k = (1, -1). */
  vfloat a = map(v3(p.x + h, p.y - h, p.z - h));
  vfloat b = map(v3(p.x - h, p.y - h, p.z + h));
  vfloat c = map(v3(p.x - h, p.y + h, p.z - h));
  vfloat d = map(v3(p.x + h, p.y + h, p.z + h));
  return v3_normalize(v3(a - b - c + d, -a - b + c + d, -a + b - c + d));
}
#else
SDF_INLINE vec3v estimate_normal(vec3v p, float h) {
  vfloat dx = map(v3(p.x + h, p.y, p.z)) - map(v3(p.x - h, p.y, p.z));
  vfloat dy = map(v3(p.x, p.y + h, p.z)) - map(v3(p.x, p.y - h, p.z));
  vfloat dz = map(v3(p.x, p.y, p.z + h)) - map(v3(p.x, p.y, p.z - h));
  return v3_normalize(v3(dx, dy, dz));
}
#endif
