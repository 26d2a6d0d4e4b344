/* Distance functions of the primitives (Inigo Quilez's list), one per node kind of
 * host/scene/node_kinds.def. Each takes the sample point first, in the node's local frame, and
 * says whether it returns the exact distance or a bound. Vector parameters arrive as float4
 * literals (xyz used). */

/* Exact. */
SDF_INLINE vfloat sd_sphere(vec3v p, float4 center, float radius) {
  return v3_length(v3_sub(p, v3_from(center))) - radius;
}

/* Exact. */
SDF_INLINE vfloat sd_box(vec3v p, float4 center, float4 half_size) {
  vec3v q = v3_sub(v3_abs(v3_sub(p, v3_from(center))), v3_from(half_size));
  return v3_length(v3_max0(q)) + fmin(v3_max_component(q), 0.0f);
}

/* Exact; half_size includes the rounding radius. */
SDF_INLINE vfloat sd_round_box(vec3v p, float4 center, float4 half_size, float radius) {
  vec3v q = v3_sub(v3_abs(v3_sub(p, v3_from(center))),
                   v3_from(half_size - radius));
  return v3_length(v3_max0(q)) + fmin(v3_max_component(q), 0.0f) - radius;
}

/* Exact. The three terms are the bars along x, y and z. */
SDF_INLINE vfloat sd_box_frame(vec3v p, float4 center, float4 half_size, float thickness) {
  vec3v a = v3_sub(v3_abs(v3_sub(p, v3_from(center))), v3_from(half_size));
  vec3v q = v3_sub(v3_abs(v3_add(a, v3_splat(thickness))), v3_splat(thickness));
  vec3v bar_x = v3(a.x, q.y, q.z);
  vec3v bar_y = v3(q.x, a.y, q.z);
  vec3v bar_z = v3(q.x, q.y, a.z);
  vfloat dx = v3_length(v3_max0(bar_x)) + fmin(v3_max_component(bar_x), 0.0f);
  vfloat dy = v3_length(v3_max0(bar_y)) + fmin(v3_max_component(bar_y), 0.0f);
  vfloat dz = v3_length(v3_max0(bar_z)) + fmin(v3_max_component(bar_z), 0.0f);
  return fmin(fmin(dx, dy), dz);
}

/* Exact. Torus in the xz plane. */
SDF_INLINE vfloat sd_torus(vec3v p, float4 center, float major_radius, float minor_radius) {
  vec3v q = v3_sub(p, v3_from(center));
  vfloat ring = vsqrt(q.x * q.x + q.z * q.z) - major_radius;
  return vsqrt(ring * ring + q.y * q.y) - minor_radius;
}

/* Exact. normal is unit length (the loader normalises it). */
SDF_INLINE vfloat sd_plane(vec3v p, float4 normal, float offset) {
  return p.x * normal.x + p.y * normal.y + p.z * normal.z + offset;
}

/* Exact. Segment a-b thickened by radius. */
SDF_INLINE vfloat sd_capsule(vec3v p, float4 a, float4 b, float radius) {
  vec3v pa = v3_sub(p, v3_from(a));
  float4 ba = b - a;
  vfloat h = clamp((pa.x * ba.x + pa.y * ba.y + pa.z * ba.z) / dot(ba.xyz, ba.xyz), 0.0f, 1.0f);
  return v3_length(v3_sub(pa, v3_scale(v3_from(ba), h))) - radius;
}

/* Exact. Capped cylinder along y. */
SDF_INLINE vfloat sd_cylinder(vec3v p, float4 center, float radius, float half_height) {
  vec3v q = v3_sub(p, v3_from(center));
  vfloat dr = vsqrt(q.x * q.x + q.z * q.z) - radius;
  vfloat dh = fabs(q.y) - half_height;
  vfloat outside_r = fmax(dr, 0.0f);
  vfloat outside_h = fmax(dh, 0.0f);
  return fmin(fmax(dr, dh), 0.0f) + vsqrt(outside_r * outside_r + outside_h * outside_h);
}

/* Exact. Infinite cylinder along y, its axis through center. */
SDF_INLINE vfloat sd_infinite_cylinder(vec3v p, float4 center, float radius) {
  vfloat dx = p.x - center.x;
  vfloat dz = p.z - center.z;
  return vsqrt(dx * dx + dz * dz) - radius;
}
