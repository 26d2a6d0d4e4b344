/* The camera contract (docs/scene-format.md) on the device: the basis comes from the host
 * (host/scene/camera_model.cpp, double precision); each lane builds its pixel's ray from it. */

/* The unnormalised direction through the image point (x, y) in pixel units (pixel centres at
 * i + 0.5), one per work-item: f + sx r + sy u, whose length is at least 1. camera_ray_at is the
 * same per lane. */
SDF_INLINE float4 camera_plane_point(const MarchParams* params, float x, float y) {
  const float sx = x * (2.0f / (float)params->width) - 1.0f;
  const float sy = 1.0f - y * (2.0f / (float)params->height);
  return params->forward + sx * params->right_extent + sy * params->up_extent;
}

/* The unit direction through the image point (x, y) in pixel units, per lane. */
SDF_INLINE vec3v camera_ray_at(const MarchParams* params, vfloat x, vfloat y) {
  /* Reciprocals once per packet: a division per lane is the slowest vector operation here. */
  const float x_scale = 2.0f / (float)params->width;
  const float y_scale = 2.0f / (float)params->height;
  const vfloat sx = x * x_scale - 1.0f;
  const vfloat sy = 1.0f - y * y_scale;
  vec3v dir = v3_add(v3_from(params->forward),
                     v3_add(v3_scale(v3_from(params->right_extent), sx), v3_scale(v3_from(params->up_extent), sy)));
  return v3_normalize(dir);
}

/* The ray through the centre of pixel (i, j), per lane. */
SDF_INLINE vec3v camera_ray(const MarchParams* params, vint i, vint j) {
  return camera_ray_at(params, TO_VFLOAT(i) + 0.5f, TO_VFLOAT(j) + 0.5f);
}
