/* The throughput ceiling of `clmarch bench`: the distance field evaluated at exactly the points
 * the march evaluated (recorded by the march kernel built with RECORD_SAMPLES), packed densely,
 * LANES consecutive points per work-item: no march bookkeeping, no idle lanes, no early exit.
 * Each point is evaluated `repeats` times, shifted by k * REPLAY_SHIFT along x (a few ulps at
 * most, so the cost stays the point's, but the compiler cannot merge the evaluations), so that
 * reading 12 bytes per point does not limit the rate. The distances are summed so no
 * evaluation can be optimised away; each lane counts its evaluations, which the host checks. */

#define REPLAY_SHIFT 1e-7f

__kernel void replay_samples(__global const float* samples, const int count, const int stride, const int repeats,
                             __global float* sums, __global int* evaluations, SceneValues values) {
  const int base = (int)get_global_id(0) * LANES;
  const vint live = MASK(base + LANE_IOTA < count);
  const vec3v p =
      v3(LOAD_LANES(base, samples), LOAD_LANES(base, samples + stride), LOAD_LANES(base, samples + 2 * stride));
  vfloat sum = (vfloat)(0.0f);
  vint counted = (vint)(0);
  for (int k = 0; k < repeats; ++k) {
    sum += field(values, v3(p.x + (float)k * REPLAY_SHIFT, p.y, p.z));
    counted -= live; /* live lanes are -1 */
  }
  STORE_LANES(sum, base, sums);
  STORE_INT_LANES(counted, base, evaluations);
}
