/* The sphere-tracing kernel: each work-item marches one packet, a tile of PACKET_WIDTH x
 * PACKET_HEIGHT pixels, in lock-step (the loops: march_loop.cl, tiling.cl), then writes depth (+inf
 * on a miss), steps and wall steps, and with NEED_NORMALS / NEED_SHADING the normal and the final
 * color, into planes of out (CLMARCH_CHANNEL_*), plane_stride floats each. A dispatch covers the
 * image rows first_row .. first_row + chunk_rows - 1; a plane holds them row by row. */

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

/* Writes one value per lane into a plane: whole tiles as rows of vector stores, tiles cut by the
 * image's right or bottom edge lane by lane (columns x rows of them are inside). */
SDF_INLINE void store_tile(vfloat v, int at, int width, int columns, int rows, __global float* plane) {
  if (columns == PACKET_WIDTH && rows == PACKET_HEIGHT) {
    STORE_TILE(v, at, width, plane);
    return;
  }
  float values[LANES];
  STORE_LANES(v, 0, values);
  for (int lane = 0; lane < LANES; ++lane) {
    const int x = lane % PACKET_WIDTH, y = lane / PACKET_WIDTH;
    if (x < columns && y < rows) plane[at + y * width + x] = values[lane];
  }
}

#if defined(RECORD_SAMPLES)
/* The first sample index of each lane's ray (sample_base: one int per image pixel, row-major;
 * columns x rows of the tile at pixel `at` are inside the image, the others get -1). */
SDF_INLINE vint tile_sample_base(__global const int* sample_base, int at, int width, int columns, int rows) {
  mask1 bases[LANES];
  for (int lane = 0; lane < LANES; ++lane) {
    const int x = lane % PACKET_WIDTH, y = lane / PACKET_WIDTH;
    bases[lane] = x < columns && y < rows ? sample_base[at + y * width + x] : -1;
  }
#if LANES == 1
  return bases[0];
#else
  return VLOAD_LANES(0, bases);
#endif
}
#endif

__kernel void march(const MarchParams params, __global float* out, __constant float4* lights
#if defined(RECORD_SAMPLES)
                    , __global const int* sample_base, __global float* samples, const int sample_stride
#endif
) {
  const int tiles_per_row = (params.width + PACKET_WIDTH - 1) / PACKET_WIDTH;
  const int item = (int)get_global_id(0);
  const int tile_row = item / tiles_per_row;
  const int x0 = (item - tile_row * tiles_per_row) * PACKET_WIDTH;
  const int row0 = tile_row * PACKET_HEIGHT; /* within the chunk */
  const int y0 = params.first_row + row0;
  const int rows = min(min(PACKET_HEIGHT, params.chunk_rows - row0), params.height - y0);
  if (rows <= 0) return; /* padding of the dispatch to whole work-groups */
  const int columns = min(PACKET_WIDTH, params.width - x0);
  const vint live = MASK(LANE_X < columns) & MASK(LANE_Y < rows);
  const vec3v dir = camera_ray(&params, x0 + LANE_X, y0 + LANE_Y);
#if defined(TILING_CELLS)
  const vec3v origin = v3_from(params.origin_in_cell);
#else
  const vec3v origin = v3_from(params.origin);
#endif
  MarchLimits limits = {params.max_steps, params.epsilon, 0, 0.0f, params.over_relaxation, params.hit_cone_slope};
#if defined(RECORD_SAMPLES)
  limits.samples = samples;
  limits.sample_stride = sample_stride;
  limits.sample_base = tile_sample_base(sample_base, y0 * params.width + x0, params.width, columns, rows);
#endif
  vint marching = live;
  vfloat t_start = (vfloat)(0.0f);
  vfloat t_end = (vfloat)(params.max_distance);
  if (params.bounds.w > 0.0f) {
    clip_to_bounds(params.bounds, dir, &marching, &t_start, &t_end);
  }
  const MarchResult m = MARCH(origin, dir, marching, t_start, t_end, limits);

  const int stride = params.plane_stride;
  const int at = row0 * params.width + x0;
#define STORE_PLANE(channel, v) store_tile((v), at, params.width, columns, rows, out + (channel) * stride)
  STORE_PLANE(CLMARCH_CHANNEL_DEPTH, select((vfloat)(INFINITY), m.t, m.hit));
  STORE_PLANE(CLMARCH_CHANNEL_STEPS, m.steps);
#if defined(TILING_CELLS)
  STORE_PLANE(CLMARCH_CHANNEL_WALL_STEPS, m.wall_steps);
#endif

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
  STORE_PLANE(CLMARCH_CHANNEL_NX, normal.x);
  STORE_PLANE(CLMARCH_CHANNEL_NY, normal.y);
  STORE_PLANE(CLMARCH_CHANNEL_NZ, normal.z);
#ifdef NEED_SHADING
  color = tone_map(color);
  STORE_PLANE(CLMARCH_CHANNEL_R, color.x);
  STORE_PLANE(CLMARCH_CHANNEL_G, color.y);
  STORE_PLANE(CLMARCH_CHANNEL_B, color.z);
#endif
#endif
#undef STORE_PLANE
  (void)lights;
}
