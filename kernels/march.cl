/* The sphere-tracing kernel: each work-item marches LANES consecutive pixels in lock-step (the
 * loops: march_loop.cl, tiling.cl), then writes depth (+inf on a miss), steps and wall steps, and
 * with NEED_NORMALS / NEED_SHADING the normal and the lit color, into planes of out
 * (CLMARCH_CHANNEL_*), plane_stride floats each. */

__kernel void march(const MarchParams params, __global float* out, __constant float4* lights) {
  const int base = (int)get_global_id(0) * LANES;
  const vint pixel = params.first_pixel + base + LANE_IOTA;
  const vint live = MASK(pixel < params.pixel_count);
  const vec3v dir = camera_ray(&params, pixel % params.width, pixel / params.width);
#if defined(TILING_CELLS)
  const MarchResult m = march_cells(&params, live, dir);
#elif defined(TILING_MOD)
  const MarchResult m = march_mod(&params, live, v3_from(params.origin), dir);
#else
  const MarchResult m = march_plain(&params, live, v3_from(params.origin), dir);
#endif

  const int stride = params.plane_stride;
  STORE_LANES(select((vfloat)(INFINITY), m.t, m.hit), base, out + CLMARCH_CHANNEL_DEPTH * stride);
  STORE_LANES(m.steps, base, out + CLMARCH_CHANNEL_STEPS * stride);
  STORE_LANES(m.wall_steps, base, out + CLMARCH_CHANNEL_WALL_STEPS * stride);

#ifdef NEED_NORMALS
  vec3v normal = v3_splat(0.0f);
#ifdef NEED_SHADING
  vec3v color = v3_from(BACKGROUND_COLOR);
#endif
  if (LANE_ANY(m.hit)) {
    normal = v3_select(v3_splat(0.0f), estimate_normal(m.local_point, params.normal_epsilon), m.hit);
#ifdef NEED_SHADING
    vec3v albedo;
    map_color(m.local_point, &albedo);
    const vec3v lit = shade(v3_scale(dir, m.t), m.t, normal, v3_scale(dir, -1.0f), m.steps, albedo, lights);
    color = v3_select(color, lit, m.hit);
#endif
  }
  STORE_LANES(normal.x, base, out + CLMARCH_CHANNEL_NX * stride);
  STORE_LANES(normal.y, base, out + CLMARCH_CHANNEL_NY * stride);
  STORE_LANES(normal.z, base, out + CLMARCH_CHANNEL_NZ * stride);
#ifdef NEED_SHADING
  STORE_LANES(color.x, base, out + CLMARCH_CHANNEL_R * stride);
  STORE_LANES(color.y, base, out + CLMARCH_CHANNEL_G * stride);
  STORE_LANES(color.z, base, out + CLMARCH_CHANNEL_B * stride);
#endif
#endif
  (void)lights;
}
