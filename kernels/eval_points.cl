/* Evaluates the scene's distance function, material and primitive number at batches of points (LANES per
 * work-item), for tests against closed forms. Inputs and outputs are planes of floats, padded to
 * whole packets. */

__kernel void eval_points(__global const float* xs, __global const float* ys, __global const float* zs,
                          __global float* distance, __global float* color_distance, __global float* red,
                          __global float* green, __global float* blue, __global float* ids, SceneValues values) {
  const int base = (int)get_global_id(0) * LANES;
  const vec3v p = v3(LOAD_LANES(base, xs), LOAD_LANES(base, ys), LOAD_LANES(base, zs));
  vec3v albedo, surface, emission;
  vfloat id;
  STORE_LANES(map(values, p), base, distance);
  STORE_LANES(map_color(values, p, &albedo, &surface, &emission, &id), base, color_distance);
  STORE_LANES(id, base, ids);
  STORE_LANES(albedo.x, base, red);
  STORE_LANES(albedo.y, base, green);
  STORE_LANES(albedo.z, base, blue);
}
