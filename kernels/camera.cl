/* The camera contract (docs/scene-format.md) on the device: the basis comes from the host
 * (host/scene/camera_model.cpp, double precision); each lane builds its pixel's ray from it. */

SDF_INLINE vec3v camera_ray(const MarchParams* params, vint i, vint j) {
  /* Reciprocals once per packet: a division per lane is the slowest vector operation here. */
  const float x_scale = 2.0f / (float)params->width;
  const float y_scale = 2.0f / (float)params->height;
  const vfloat sx = (TO_VFLOAT(i) + 0.5f) * x_scale - 1.0f;
  const vfloat sy = 1.0f - (TO_VFLOAT(j) + 0.5f) * y_scale;
  vec3v dir = v3_add(v3_from(params->forward),
                     v3_add(v3_scale(v3_from(params->right_extent), sx), v3_scale(v3_from(params->up_extent), sy)));
  return v3_normalize(dir);
}
