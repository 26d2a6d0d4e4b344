/* Evaluates the scene's distance function at batches of points (LANES per work-item): eval_points
 * with the albedo for tests against closed forms, eval_ceiling as the divergence-free throughput
 * ceiling of benchmarks. Inputs and outputs are planes of floats, padded to whole packets. */

__kernel void eval_points(__global const float* xs, __global const float* ys, __global const float* zs,
                          __global float* distance, __global float* color_distance, __global float* red,
                          __global float* green, __global float* blue) {
  const int base = (int)get_global_id(0) * LANES;
  const vec3v p = v3(LOAD_LANES(base, xs), LOAD_LANES(base, ys), LOAD_LANES(base, zs));
  vec3v albedo, surface;
  STORE_LANES(map(p), base, distance);
  STORE_LANES(map_color(p, &albedo, &surface), base, color_distance);
  STORE_LANES(albedo.x, base, red);
  STORE_LANES(albedo.y, base, green);
  STORE_LANES(albedo.z, base, blue);
}

/* The throughput ceiling of `clmarch bench`: map() at the points start + k * step, k = 0 .. depths-1,
 * of each lane's ray (the host passes camera rays), every lane evaluating every point in lock-step:
 * no early exit, no divergence, and only 6 floats read per depths evaluations, so the time is the
 * distance function's. The distances are summed so no evaluation can be optimised away; each lane
 * counts the evaluations of its live point (index < count), which the host checks. */
__kernel void eval_ceiling(__global const float* xs, __global const float* ys, __global const float* zs,
                           __global const float* step_xs, __global const float* step_ys, __global const float* step_zs,
                           const int count, const int depths, __global float* sums, __global int* evaluations) {
  const int base = (int)get_global_id(0) * LANES;
  const vint live = MASK(base + LANE_IOTA < count);
  const vec3v start = v3(LOAD_LANES(base, xs), LOAD_LANES(base, ys), LOAD_LANES(base, zs));
  const vec3v step = v3(LOAD_LANES(base, step_xs), LOAD_LANES(base, step_ys), LOAD_LANES(base, step_zs));
  vfloat sum = (vfloat)(0.0f);
  vint counted = (vint)(0);
  for (int k = 0; k < depths; ++k) {
    sum += map(v3_add(start, v3_scale(step, (vfloat)((float)k))));
    counted -= live; /* live lanes are -1 */
  }
  STORE_LANES(sum, base, sums);
  STORE_INT_LANES(counted, base, evaluations);
}
