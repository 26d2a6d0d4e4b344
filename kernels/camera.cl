/* The camera contract (docs/scene-format.md) on the device: the basis comes from the host
 * (host/scene/camera_model.cpp, double precision); each lane builds its pixel's ray from it. */

/* A camera vector at the lanes' precision: double programs read the host's doubles (camera_double
 * from first on, CLMARCH_CAMERA_*), float programs their float4 rounding. */
SDF_INLINE vec3v camera_vector(const MarchParams* params, float4 rounded, int first) {
#ifdef DOUBLE_PRECISION
  (void)rounded;
  return v3((vfloat)(as_double(params->camera_double[first])), (vfloat)(as_double(params->camera_double[first + 1])),
            (vfloat)(as_double(params->camera_double[first + 2])));
#else
  (void)params;
  (void)first;
  return v3_from(rounded);
#endif
}

/* The unnormalised direction through the image point (x, y) in pixel units (pixel centres at
 * i + 0.5), one per work-item: f + sx r + sy u, whose length is at least 1. camera_ray_at is the
 * same per lane. Float: the tile tests' scalar arithmetic. */
SDF_INLINE float4 camera_plane_point(const MarchParams* params, float x, float y) {
  const float sx = x * (2.0f / (float)params->width) - 1.0f;
  const float sy = 1.0f - y * (2.0f / (float)params->height);
  return params->forward + sx * params->right_extent + sy * params->up_extent;
}

/* The unit direction through the image point (x, y) in pixel units, per lane. */
SDF_INLINE vec3v camera_ray_at(const MarchParams* params, vfloat x, vfloat y) {
  /* Reciprocals once per packet: a division per lane is the slowest vector operation here. */
  const real x_scale = (real)2 / (real)params->width;
  const real y_scale = (real)2 / (real)params->height;
  const vfloat sx = x * x_scale - (real)1;
  const vfloat sy = (real)1 - y * y_scale;
  const vec3v forward = camera_vector(params, params->forward, CLMARCH_CAMERA_FORWARD);
  const vec3v right = camera_vector(params, params->right_extent, CLMARCH_CAMERA_RIGHT);
  const vec3v up = camera_vector(params, params->up_extent, CLMARCH_CAMERA_UP);
  return v3_normalize(v3_add(forward, v3_add(v3_scale(right, sx), v3_scale(up, sy))));
}

/* The ray through the centre of pixel (i, j), per lane. */
SDF_INLINE vec3v camera_ray(const MarchParams* params, vint i, vint j) {
  return camera_ray_at(params, TO_VFLOAT(i) + (real)0.5f, TO_VFLOAT(j) + (real)0.5f);
}

/* Where camera rays start, in map()'s frame, or with the cells tiling in the camera's cell. */
SDF_INLINE vec3v camera_origin(const MarchParams* params) {
#if defined(TILING_CELLS)
  return camera_vector(params, params->origin_in_cell, CLMARCH_CAMERA_ORIGIN_IN_CELL);
#else
  return camera_vector(params, params->origin, CLMARCH_CAMERA_ORIGIN);
#endif
}
