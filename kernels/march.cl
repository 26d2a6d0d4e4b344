/* The sphere-tracing kernel: each work-item marches LANES consecutive pixels in lock-step (the
 * loops: march_loop.cl, tiling.cl), then writes depth (+inf on a miss), steps and wall steps, and
 * with NEED_NORMALS / NEED_SHADING the normal and the final color, into planes of out
 * (CLMARCH_CHANNEL_*), plane_stride floats each. */

#if defined(NEED_SHADING)
/* The surface met by a ray from the camera-relative point relative_origin, marched in map()'s
 * frame (m), with its normal and material. */
SDF_INLINE Hit surface_at(const MarchResult* m, vec3v relative_origin, vec3v dir, float normal_epsilon) {
  Hit hit;
  hit.point = m->local_point;
  hit.relative = v3_add(relative_origin, v3_scale(dir, m->t));
  hit.normal = estimate_normal(m->local_point, normal_epsilon);
  map_color(m->local_point, &hit.albedo, &hit.surface);
  hit.steps = m->steps;
  return hit;
}
#endif

#if defined(NEED_SHADING) && defined(REFLECTION_BOUNCES)
/* Adds the mirror bounces of the PBR course: each bounce's color weighted by the product of the
 * reflectivities met so far; a bounce that misses shows the sky. */
SDF_INLINE vec3v add_reflections(vec3v color, Hit hit, vec3v dir, vint live, const MarchParams* params, __constant float4* lights) {
  /* Mirror rays march plainly with the fixed epsilon: the pixel cone is the camera's, and their t
   * starts again at the mirror. */
  MarchLimits limits = {params->max_steps, params->epsilon, 0, 0.0f, 1.0f, 0.0f};
  vfloat weight = (vfloat)(1.0f);
  vint active = live;
  for (int bounce = 0; bounce < REFLECTION_BOUNCES; ++bounce) {
    weight *= hit.surface.z;
    active &= MASK(weight > 0.0f);
    if (!LANE_ANY(active)) break;
    /* reflect(dir, n) = dir - 2 dot(dir, n) n */
    dir = v3_sub(dir, v3_scale(hit.normal, 2.0f * v3_dot(dir, hit.normal)));
    const vec3v origin = v3_add(hit.point, v3_scale(hit.normal, REFLECTION_OFFSET));
    const vec3v relative_origin = v3_add(hit.relative, v3_scale(hit.normal, REFLECTION_OFFSET));
    const MarchResult r = MARCH(origin, dir, active, (vfloat)(0.0f), (vfloat)(params->max_distance), limits);
    vec3v seen = miss_color(dir, r.closest);
    const vint reflected_hit = active & r.hit;
    if (LANE_ANY(reflected_hit)) {
      const Hit next = surface_at(&r, relative_origin, dir, params->normal_epsilon);
      seen = v3_select(seen, shade(&next, v3_scale(dir, -1.0f), reflected_hit, lights), reflected_hit);
      hit.point = v3_select(hit.point, next.point, reflected_hit);
      hit.relative = v3_select(hit.relative, next.relative, reflected_hit);
      hit.normal = v3_select(hit.normal, next.normal, reflected_hit);
      hit.surface = v3_select(hit.surface, next.surface, reflected_hit);
    }
    color = v3_select(color, v3_add(color, v3_scale(seen, weight)), active);
    active = reflected_hit;
  }
  return color;
}
#endif

/* Camera rays march only inside the scene's bounding sphere (host/scene/scene_bounds.cpp): lanes
 * whose ray misses it do not march at all, the others start where they enter it (or at the camera)
 * and end where they leave it. bounds.xyz = camera - centre; the discriminant is taken as
 * r^2 - |offset - b dir|^2, which keeps its precision far from the sphere. */
SDF_INLINE void clip_to_bounds(float4 bounds, vec3v dir, vint* marching, vfloat* t_start, vfloat* t_end) {
  const vfloat b = bounds.x * dir.x + bounds.y * dir.y + bounds.z * dir.z;
  const vec3v closest = v3(bounds.x - b * dir.x, bounds.y - b * dir.y, bounds.z - b * dir.z);
  const vfloat h = bounds.w * bounds.w - v3_dot(closest, closest);
  const vfloat root = sqrt(fmax(h, 0.0f));
  *t_start = fmax(-b - root, 0.0f);
  *t_end = fmin(-b + root, *t_end);
  *marching &= MASK(h >= 0.0f) & MASK(*t_end > *t_start);
}

__kernel void march(const MarchParams params, __global float* out, __constant float4* lights) {
  const int base = (int)get_global_id(0) * LANES;
  const vint pixel = params.first_pixel + base + LANE_IOTA;
  const vint live = MASK(pixel < params.pixel_count);
  const vec3v dir = camera_ray(&params, pixel % params.width, pixel / params.width);
#if defined(TILING_CELLS)
  const vec3v origin = v3_from(params.origin_in_cell);
#else
  const vec3v origin = v3_from(params.origin);
#endif
  const MarchLimits limits = {params.max_steps, params.epsilon, 0, 0.0f, params.over_relaxation, params.hit_cone_slope};
  vint marching = live;
  vfloat t_start = (vfloat)(0.0f);
  vfloat t_end = (vfloat)(params.max_distance);
  if (params.bounds.w > 0.0f) {
    clip_to_bounds(params.bounds, dir, &marching, &t_start, &t_end);
  }
  const MarchResult m = MARCH(origin, dir, marching, t_start, t_end, limits);

  const int stride = params.plane_stride;
  STORE_LANES(select((vfloat)(INFINITY), m.t, m.hit), base, out + CLMARCH_CHANNEL_DEPTH * stride);
  STORE_LANES(m.steps, base, out + CLMARCH_CHANNEL_STEPS * stride);
  STORE_LANES(m.wall_steps, base, out + CLMARCH_CHANNEL_WALL_STEPS * stride);

#ifdef NEED_NORMALS
  vec3v normal = v3_splat(0.0f);
#ifdef NEED_SHADING
  vec3v color = miss_color(dir, m.closest);
#endif
  if (LANE_ANY(m.hit)) {
#ifdef NEED_SHADING
    const Hit hit = surface_at(&m, v3_splat(0.0f), dir, params.normal_epsilon);
    normal = v3_select(normal, hit.normal, m.hit);
    vec3v lit = shade(&hit, v3_scale(dir, -1.0f), m.hit, lights);
#if defined(REFLECTION_BOUNCES)
    lit = add_reflections(lit, hit, dir, m.hit, &params, lights);
#endif
    lit = apply_fog(lit, dir, m.t, params.camera_height);
    color = v3_select(color, lit, m.hit);
#else
    normal = v3_select(normal, estimate_normal(m.local_point, params.normal_epsilon), m.hit);
#endif
  }
  STORE_LANES(normal.x, base, out + CLMARCH_CHANNEL_NX * stride);
  STORE_LANES(normal.y, base, out + CLMARCH_CHANNEL_NY * stride);
  STORE_LANES(normal.z, base, out + CLMARCH_CHANNEL_NZ * stride);
#ifdef NEED_SHADING
  color = tone_map(color);
  STORE_LANES(color.x, base, out + CLMARCH_CHANNEL_R * stride);
  STORE_LANES(color.y, base, out + CLMARCH_CHANNEL_G * stride);
  STORE_LANES(color.z, base, out + CLMARCH_CHANNEL_B * stride);
#endif
#endif
  (void)lights;
}
