/* The coarse cone pass (render.coarse_pass: cone, docs/scene-format.md): before the camera rays
 * march, one cone per block of CLMARCH_COARSE_BLOCK x CLMARCH_COARSE_BLOCK pixels marches from the
 * camera, and every ray of the block starts its own march where the cone stopped (packet_at in
 * march.cl). The cones of LANES consecutive blocks march as the lanes of one work-item, so a cone
 * step costs a 64th of the steps it saves. host/reference/reference_cones.cpp is the
 * double-precision reference of the same rule.
 *
 * The cone's axis a is the ray through the middle of the block's pixel centres, and k bounds the
 * chord |u - a| of every ray u of the block: the largest of its corner rays' (the angle to a is
 * quasi-convex over the image plane), grown for rounding. At depth t the block's rays lie within
 * k t of the axis point t a; where the field there is d, a ray's points up to depth t + s keep a
 * field value of at least d - k (t + s) - s (the field is 1-Lipschitz). The cone steps the largest
 * s that keeps this at or above the hit threshold there, max(epsilon, slope (t + s)), plus
 * the margin params.shading.glow_radius (0 without glow): no ray of the block could have hit, or passed near enough to
 * glow, before its start. It stops once that step falls below COARSE_STOP_FRACTION of d, what
 * plain sphere tracing would step, or at the end of the bounding sphere or max_distance. */

#define COARSE_STOP_FRACTION 0.25f

/* The chord bound k of a block: the largest |u - a| over its corner rays, grown by a thousandth
 * and 1e-6 for the rounding of float directions. */
SDF_INLINE vfloat coarse_spread(vec3v axis, vec3v c0, vec3v c1, vec3v c2, vec3v c3) {
  const vec3v d0 = v3_sub(c0, axis), d1 = v3_sub(c1, axis), d2 = v3_sub(c2, axis), d3 = v3_sub(c3, axis);
  const vfloat chord2 = fmax(fmax(v3_dot(d0, d0), v3_dot(d1, d1)), fmax(v3_dot(d2, d2), v3_dot(d3, d3)));
  return sqrt(chord2) * 1.001f + 1e-6f;
}

/* Writes, for blocks get_global_id(0) * LANES .. + LANES - 1 of the image (row-major, blocks_x per
 * row), where their rays start (starts) and the cone's steps (steps). */
__kernel void coarse_cones(const MarchParams params, __global float* starts, __global float* steps_out,
                           SceneValues values) {
  const int blocks_x = CLMARCH_COARSE_BLOCKS(params.width);
  const int blocks_y = CLMARCH_COARSE_BLOCKS(params.height);
  const int base = (int)get_global_id(0) * LANES;
  const vint block = (vint)(base) + LANE_IOTA;
  const vint bx = block % blocks_x, by = block / blocks_x;
  /* First and last pixel centres of the block, clipped to the image. */
  const vfloat x0 = TO_VFLOAT(bx * CLMARCH_COARSE_BLOCK) + 0.5f;
  const vfloat y0 = TO_VFLOAT(by * CLMARCH_COARSE_BLOCK) + 0.5f;
  const vfloat x1 = TO_VFLOAT(min(bx * CLMARCH_COARSE_BLOCK + CLMARCH_COARSE_BLOCK, (vint)(params.width)) - 1) + 0.5f;
  const vfloat y1 = TO_VFLOAT(min(by * CLMARCH_COARSE_BLOCK + CLMARCH_COARSE_BLOCK, (vint)(params.height)) - 1) + 0.5f;
  const vec3v axis = camera_ray_at(&params, 0.5f * (x0 + x1), 0.5f * (y0 + y1));
  const vfloat k = coarse_spread(axis, camera_ray_at(&params, x0, y0), camera_ray_at(&params, x1, y0),
                                 camera_ray_at(&params, x0, y1), camera_ray_at(&params, x1, y1));

  /* The bounding sphere (bounds.xyz = camera - centre, w = radius) holds every hit: the cone starts
   * where the sphere's nearest point is and ends past its farthest. */
  float t_first = 0.0f, t_last = params.max_distance;
  if (params.bounds.w > 0.0f) {
    const float distance =
        sqrt(params.bounds.x * params.bounds.x + params.bounds.y * params.bounds.y + params.bounds.z * params.bounds.z);
    t_first = fmax(distance - params.bounds.w, 0.0f);
    t_last = fmin(distance + params.bounds.w, t_last);
  }
  /* The kernel's rays also arrive below REAL_EPSILON t (hit_threshold in march_loop.cl). */
  const float slope = fmax(params.hit_cone_slope, (float)REAL_EPSILON);
  const float margin = params.shading.glow_radius;
  const float floor_threshold = params.epsilon + margin;

  const vec3v origin = camera_origin(&params);
  vfloat t = (vfloat)(t_first);
  vfloat steps = (vfloat)(0.0f);
  vint active = MASK(block < blocks_x * blocks_y) & MASK(t < (vfloat)(t_last));
  for (int step = 0; step < params.max_steps && LANE_ANY(active); ++step) {
    const vfloat d = field(values, v3_add(origin, v3_scale(axis, t)));
    steps += select((vfloat)(0.0f), (vfloat)(1.0f), active);
    const vfloat s =
        fmin((d - floor_threshold - k * t) / (1.0f + k), (d - margin - (k + slope) * t) / (1.0f + k + slope));
    active &= MASK(s >= COARSE_STOP_FRACTION * d);
    t = select(t, fmin(t + s, (vfloat)(t_last)), active);
    active &= MASK(t < (vfloat)(t_last));
  }
  STORE_LANES(t, base, starts);
  STORE_LANES(steps, base, steps_out);
}
