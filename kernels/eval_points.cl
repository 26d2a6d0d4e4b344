/* Evaluates the scene's distance function, material and primitive number at batches of points (LANES per
 * work-item): for tests against closed forms, clmarch.field and the samples of clmarch mesh. Inputs and
 * outputs are planes of floats, padded to whole packets. Each point is origin + (x, y, z): origin comes
 * as a float pair hi + lo, which a double program adds in double, so that the points near a far origin
 * keep the precision of their offsets. */

__kernel void eval_points(__global const float* xs, __global const float* ys, __global const float* zs,
                          __global float* distance, __global float* color_distance, __global float* red,
                          __global float* green, __global float* blue, __global float* ids, SceneValues values,
                          const float4 origin_hi, const float4 origin_lo) {
  const int base = (int)get_global_id(0) * LANES;
  const real ox = (real)origin_hi.x + (real)origin_lo.x;
  const real oy = (real)origin_hi.y + (real)origin_lo.y;
  const real oz = (real)origin_hi.z + (real)origin_lo.z;
  const vec3v p = v3(LOAD_LANES(base, xs) + ox, LOAD_LANES(base, ys) + oy, LOAD_LANES(base, zs) + oz);
  vec3v albedo, surface, emission;
  vfloat id;
  STORE_LANES(map(values, p), base, distance);
  STORE_LANES(map_color(values, p, &albedo, &surface, &emission, &id), base, color_distance);
  STORE_LANES(id, base, ids);
  STORE_LANES(albedo.x, base, red);
  STORE_LANES(albedo.y, base, green);
  STORE_LANES(albedo.z, base, blue);
}
