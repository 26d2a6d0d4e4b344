/* The sphere-tracing kernel: each work-item marches LANES consecutive pixels in lock-step, a lane
 * going idle once its ray hits (distance < epsilon), passes max_distance or the step budget ends
 * (both misses). Writes depth (+inf on a miss) and steps, and with NEED_NORMALS / NEED_SHADING
 * the normal and the lit color, into planes of out (CLMARCH_CHANNEL_*), plane_stride floats each. */

__kernel void march(const MarchParams params, __global float* out) {
  const int base = (int)get_global_id(0) * LANES;
  const vint pixel = params.first_pixel + base + LANE_IOTA;
  const vint live = MASK(pixel < params.pixel_count);
  const vec3v origin = v3_from(params.origin);
  const vec3v dir = camera_ray(&params, pixel % params.width, pixel / params.width);

  vfloat t = (vfloat)(0.0f);
  vfloat steps = (vfloat)(0.0f);
  vint active = live;
  vint hit = (vint)(0);
  for (int step = 0; step < params.max_steps && LANE_ANY(active); ++step) {
    vfloat d = map(v3_add(origin, v3_scale(dir, t)));
    steps += select((vfloat)(0.0f), (vfloat)(1.0f), active);
    vint arrived = active & MASK(d < params.epsilon);
    hit |= arrived;
    active &= ~arrived;
    t = select(t, t + d, active);
    active &= MASK(t < params.max_distance);
  }

  const int stride = params.plane_stride;
  STORE_LANES(select((vfloat)(INFINITY), t, hit), base, out + CLMARCH_CHANNEL_DEPTH * stride);
  STORE_LANES(steps, base, out + CLMARCH_CHANNEL_STEPS * stride);

#ifdef NEED_NORMALS
  vec3v normal = v3_splat(0.0f);
#ifdef NEED_SHADING
  vec3v color = v3_from(BACKGROUND_COLOR);
#endif
  if (LANE_ANY(hit)) {
    const vec3v p = v3_add(origin, v3_scale(dir, t));
    normal = v3_select(v3_splat(0.0f), estimate_normal(p, params.normal_epsilon), hit);
#ifdef NEED_SHADING
    vec3v albedo;
    map_color(p, &albedo);
    color = v3_select(color, shade(p, normal, v3_scale(dir, -1.0f), steps, albedo), hit);
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
}
