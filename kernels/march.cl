/* The sphere-tracing kernel: each work-item marches PACKETS_PER_ITEM packets, each a tile of
 * PACKET_WIDTH x PACKET_HEIGHT pixels in lock-step (the loops: march_loop.cl, tiling.cl), then
 * writes depth (+inf on a miss), steps, wall steps under the cells tiling, and with WRITE_NORMALS /
 * WRITE_IDS / NEED_SHADING the normal, the primitive hit and the final color, into planes of out (CLMARCH_CHANNEL_*),
 * plane_stride floats each, for every pixel: the host reads these planes back as they are
 * (host/codegen/kernel_source.cpp, MarchOutputs). A dispatch covers the image rows first_row ..
 * first_row + chunk_rows - 1; a plane holds them row by row. */

#if defined(NEED_SHADING)
/* The surface met by a ray from the camera-relative point relative_origin, marched in map()'s
 * frame (m), with its normal and material. */
SDF_STAGE Hit surface_at(SceneValues values, const MarchResult* m, vec3v relative_origin, vec3v dir,
                         float normal_epsilon) {
  Hit hit;
  hit.point = m->local_point;
  hit.relative = v3_add(relative_origin, v3_scale(dir, m->t));
  hit.normal = estimate_normal(values, m->local_point, normal_epsilon);
#if defined(WRITE_IDS)
  map_color(values, m->local_point, &hit.albedo, &hit.surface, &hit.emission, &hit.id);
#else
  map_color(values, m->local_point, &hit.albedo, &hit.surface, &hit.emission);
#endif
  hit.steps = m->steps;
  return hit;
}
#endif

#if defined(NEED_SHADING) && defined(REFLECTIONS)
/* Adds the mirror bounces of the PBR course: each bounce's color weighted by the product of the
 * reflectivities met so far; a bounce that misses shows the sky. */
SDF_CALLED vec3v add_reflections(SceneValues values, vec3v color, Hit hit, vec3v dir, vint live,
                                 const MarchParams* params, __global const LightParams* lights) {
  const ShadingParams* shading = &params->shading;
  /* Mirror rays march plainly with the fixed epsilon, inside the scene's bounds: the pixel cone is
   * the camera's, and their t starts again at the mirror. */
  MarchLimits limits = {values, params->max_steps,  params->epsilon, CLMARCH_SHADOW_HARD, 0.0f, 1.0f,
                        0.0f,   params->cell_bounds};
  vfloat weight = (vfloat)(1.0f);
  vint active = live;
  for (int bounce = 0; bounce < shading->reflection_bounces; ++bounce) {
    weight *= hit.surface.z;
    active &= MASK(weight > 0.0f);
    if (!LANE_ANY(active)) break;
    /* reflect(dir, n) = dir - 2 dot(dir, n) n */
    dir = v3_sub(dir, v3_scale(hit.normal, 2.0f * v3_dot(dir, hit.normal)));
    const vec3v origin = v3_add(hit.point, v3_scale(hit.normal, shading->reflection_offset));
    const vec3v relative_origin = v3_add(hit.relative, v3_scale(hit.normal, shading->reflection_offset));
    vint marching = active;
    vfloat t_start = (vfloat)(0.0f), t_end = (vfloat)(params->max_distance);
    clip_to_scene_bounds(params, relative_origin, dir, 1, &marching, &t_start, &t_end);
    const MarchResult r = MARCH(origin, dir, marching, t_start, t_end, limits);
    vec3v seen = miss_color(shading, dir, r.closest);
    const vint reflected_hit = active & r.hit;
    if (LANE_ANY(reflected_hit)) {
      const Hit next = surface_at(values, &r, relative_origin, dir, params->normal_epsilon);
      seen = v3_select(seen, shade(values, params, &next, v3_scale(dir, -1.0f), reflected_hit, lights), reflected_hit);
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

/* Camera rays march only inside the scene's bounding sphere and box (host/scene/scene_bounds.cpp,
 * scene_box.cpp): lanes whose ray misses them do not march at all, the others start where they
 * enter them (or at the camera) and end where they leave them. */
SDF_INLINE void clip_to_bounds(const MarchParams* params, vec3v dir, vint* marching, vfloat* t_start, vfloat* t_end) {
  /* A lane whose ray misses the sphere starts (and ends: the status channel) at 0, as in the
   * reference, not at its closest approach, which may lie past max_distance. */
  *t_start = (vfloat)(0.0f);
  clip_to_scene_bounds(params, v3_splat(0.0f), dir, 1, marching, t_start, t_end);
}

/* Writes one value per lane into a plane: whole tiles as rows of vector stores, tiles cut by the
 * image's right or bottom edge lane by lane (columns x rows of them are inside). */
SDF_INLINE void store_tile(vfloat v, int at, int width, int columns, int rows, __global float* plane) {
  if (columns == PACKET_WIDTH && rows == PACKET_HEIGHT) {
    STORE_TILE(v, at, width, plane);
    return;
  }
  float lane_values[LANES];
  STORE_LANES(v, 0, lane_values);
  for (int lane = 0; lane < LANES; ++lane) {
    const int x = lane % PACKET_WIDTH, y = lane / PACKET_WIDTH;
    if (x < columns && y < rows) plane[at + y * width + x] = lane_values[lane];
  }
}

/* Where the march records its points (RECORD_SAMPLES; kernels/replay.cl): per-pixel first indices
 * and the x, y, z planes of samples. An empty record otherwise. */
typedef struct {
#if defined(RECORD_SAMPLES)
  __global const int* sample_base;
  __global float* samples;
  int sample_stride;
#else
  int unused;
#endif
} MarchRecord;

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

/* A packet's tile and camera rays. */
typedef struct {
  int x0, row0;      /* its first pixel: column, and row within the dispatch's chunk */
  int columns, rows; /* of its PACKET_WIDTH x PACKET_HEIGHT pixels, those inside the image */
  vec3v dir;
  vint marching; /* lanes whose ray marches: inside the image and meeting the bounds */
  vfloat t_start, t_end;
} Packet;

/* Whether no ray through the tile whose top-left pixel is (x0, y0) can meet the bounding sphere.
 * Tiles outside the host's range of live tiles (MarchParams live_columns, live_rows) are told by
 * integer comparisons; inside it, one scalar test without a square root decides: the host's
 * tile_reach.x is reach^2 (host/render/device_inputs.cpp: the sphere's radius plus how far the
 * tile's rays spread from its centre ray, times |c|), and the centre ray q passes the sphere's
 * centre c at |c x q| / |q|. */
SDF_INLINE int tile_misses_bounds(const MarchParams* params, int x0, int y0) {
  const int column = x0 / PACKET_WIDTH, row = y0 / PACKET_HEIGHT;
  if (column < params->live_columns[0] || column > params->live_columns[1] || row < params->live_rows[0] ||
      row > params->live_rows[1]) {
    return 1;
  }
  const float4 c = params->bounds; /* xyz = camera - centre; |c x q| is the same for -c */
  const float4 q = camera_plane_point(params, (float)x0 + 0.5f * PACKET_WIDTH, (float)y0 + 0.5f * PACKET_HEIGHT);
  const float cross_x = c.y * q.z - c.z * q.y, cross_y = c.z * q.x - c.x * q.z, cross_z = c.x * q.y - c.y * q.x;
  return cross_x * cross_x + cross_y * cross_y + cross_z * cross_z >
         params->tile_reach.x * (q.x * q.x + q.y * q.y + q.z * q.z);
}

/* Packet number `index` of the chunk, tiles in row-major order; rows <= 0 past the chunk. Without
 * shading, a tile that misses the bounding sphere gets no rays: no lane marches, and its pixels
 * are written as misses with no step; a shaded miss still needs its ray for the sky. With the
 * coarse pass its rays start no earlier than their block's cone stopped (coarse_starts, one per
 * block; a tile lies inside one block, since its sides divide CLMARCH_COARSE_BLOCK). */
SDF_INLINE Packet packet_at(const MarchParams* params, int index, __global const float* coarse_starts) {
  const int tiles_per_row = (params->width + PACKET_WIDTH - 1) / PACKET_WIDTH;
  const int tile_row = index / tiles_per_row;
  Packet k;
  k.x0 = (index - tile_row * tiles_per_row) * PACKET_WIDTH;
  k.row0 = tile_row * PACKET_HEIGHT;
  const int y0 = params->first_row + k.row0;
  k.rows = min(min(PACKET_HEIGHT, params->chunk_rows - k.row0), params->height - y0);
  k.columns = min(PACKET_WIDTH, params->width - k.x0);
  k.t_start = (vfloat)(0.0f);
  k.t_end = (vfloat)(params->max_distance);
#if !defined(NEED_SHADING)
  if (params->bounds.w > 0.0f && tile_misses_bounds(params, k.x0, y0)) {
    k.dir = v3_splat(0.0f);
    k.marching = (vint)(0);
    return k;
  }
#endif
  k.dir = camera_ray(params, k.x0 + LANE_X, y0 + LANE_Y);
  k.marching = MASK(LANE_X < k.columns) & MASK(LANE_Y < k.rows);
  clip_to_bounds(params, k.dir, &k.marching, &k.t_start, &k.t_end);
#if defined(COARSE_PASS)
  const int blocks_x = CLMARCH_COARSE_BLOCKS(params->width);
  const real cone_start = coarse_starts[(y0 / CLMARCH_COARSE_BLOCK) * blocks_x + k.x0 / CLMARCH_COARSE_BLOCK];
  k.t_start = fmax(k.t_start, cone_start);
  k.marching &= MASK(k.t_start < k.t_end);
#else
  (void)coarse_starts;
#endif
  return k;
}

/* The march limits of camera rays; with RECORD_SAMPLES, where the packet's points go. */
SDF_INLINE MarchLimits camera_limits(SceneValues values, const MarchParams* params, const Packet* k,
                                     const MarchRecord* record) {
  MarchLimits limits = {values, params->max_steps,       params->epsilon,        CLMARCH_SHADOW_HARD,
                        0.0f,   params->over_relaxation, params->hit_cone_slope, params->cell_bounds};
#if defined(RECORD_SAMPLES)
  limits.samples = record->samples;
  limits.sample_stride = record->sample_stride;
  limits.sample_base = tile_sample_base(record->sample_base, (params->first_row + k->row0) * params->width + k->x0,
                                        params->width, k->columns, k->rows);
#else
  (void)k;
  (void)record;
#endif
  return limits;
}

#ifdef NEED_SHADING
/* A term of a hit's color as it reaches the camera through the fog along dir over t: fog is
 * c -> c f + g, and the term's share of the fogged color is term f = fog(term) - fog(0). */
SDF_INLINE vec3v fogged_term(const ShadingParams* shading, vec3v term, vec3v dir, vfloat t, float camera_height) {
  return v3_sub(apply_fog(shading, term, dir, t, camera_height),
                apply_fog(shading, v3_splat(0.0f), dir, t, camera_height));
}

/* The shaded, tone-mapped color of packet k's rays (the sky's where they miss), and the normals at
 * their hits (0 where they miss), with WRITE_IDS the numbers of the primitives hit (-1 where they
 * miss) and with WRITE_LAYERS the terms of their lit colors through the fog (0 where they miss). */
SDF_INLINE vec3v packet_color(SceneValues values, const Packet* k, const MarchResult* m, const MarchParams* params,
                              __global const LightParams* lights, vec3v* normal, vfloat* id, LightTerms* layers) {
  const ShadingParams* shading = &params->shading;
  *normal = v3_splat(0.0f);
  *id = (vfloat)(-1.0f);
  layers->ambient = layers->diffuse = layers->specular = v3_splat(0.0f);
  vec3v color = miss_color(shading, k->dir, m->closest);
  if (LANE_ANY(m->hit)) {
    const Hit hit = surface_at(values, m, v3_splat(0.0f), k->dir, params->normal_epsilon);
    *normal = v3_select(*normal, hit.normal, m->hit);
#if defined(WRITE_IDS)
    *id = select(*id, hit.id, m->hit);
#endif
    const LightTerms terms = light_terms(values, params, &hit, v3_scale(k->dir, -1.0f), m->hit, lights);
    vec3v lit = lit_color(shading, &terms, hit.steps);
#if defined(REFLECTIONS)
    lit = add_reflections(values, lit, hit, k->dir, m->hit, params, lights);
#endif
    lit = apply_fog(shading, lit, k->dir, m->t, params->camera_height);
    color = v3_select(color, lit, m->hit);
#if defined(WRITE_LAYERS)
    const float height = params->camera_height;
    layers->ambient = v3_select(layers->ambient, fogged_term(shading, terms.ambient, k->dir, m->t, height), m->hit);
    layers->diffuse = v3_select(layers->diffuse, fogged_term(shading, terms.diffuse, k->dir, m->t, height), m->hit);
    layers->specular = v3_select(layers->specular, fogged_term(shading, terms.specular, k->dir, m->t, height), m->hit);
#endif
  }
  return tone_map(shading, color);
}
#endif

/* Writes what the march of packet k found: depth, steps (and wall steps), and as the program
 * needs them the normal and the shaded color. */
SDF_STAGE void finish_packet(SceneValues values, const Packet* k, const MarchResult* m, const MarchParams* params,
                             __global float* out, __global const LightParams* lights) {
  const int stride = params->plane_stride;
  const int at = k->row0 * params->width + k->x0;
#define STORE_PLANE(channel, v) store_tile((v), at, params->width, k->columns, k->rows, out + (channel)*stride)
  STORE_PLANE(CLMARCH_CHANNEL_DEPTH, select((vfloat)(INFINITY), m->t, m->hit));
#if defined(WRITE_DEPTH_LO)
  STORE_PLANE(CLMARCH_CHANNEL_DEPTH_LO, select((vfloat)(0.0f), m->t - ROUNDED_TO_FLOAT(m->t), m->hit));
#endif
#if defined(WRITE_STATUS)
  /* A lane that did not march ends where it starts: 0 where its ray misses the bounding sphere,
   * its entry where that lies past max_distance (clip_to_bounds). */
  const vfloat past_end =
      select((vfloat)(CLMARCH_RAY_MISS), (vfloat)(CLMARCH_RAY_OUT_OF_DISTANCE), MASK(m->t >= params->max_distance));
  const vfloat status =
      select(select(past_end, (vfloat)(CLMARCH_RAY_OUT_OF_STEPS), m->exhausted), (vfloat)(CLMARCH_RAY_HIT), m->hit);
  STORE_PLANE(CLMARCH_CHANNEL_STATUS, status);
#endif
  STORE_PLANE(CLMARCH_CHANNEL_STEPS, m->steps);
#if defined(TILING_CELLS)
  STORE_PLANE(CLMARCH_CHANNEL_WALL_STEPS, m->wall_steps);
#endif

#ifdef NEED_NORMALS
  vec3v normal = v3_splat(0.0f);
  vfloat id = (vfloat)(-1.0f);
#ifdef NEED_SHADING
  LightTerms layers;
  const vec3v color = packet_color(values, k, m, params, lights, &normal, &id, &layers);
#if defined(WRITE_LAYERS)
  STORE_PLANE(CLMARCH_CHANNEL_AO, layers.ambient.x);
  STORE_PLANE(CLMARCH_CHANNEL_AO + 1, layers.ambient.y);
  STORE_PLANE(CLMARCH_CHANNEL_AO + 2, layers.ambient.z);
  STORE_PLANE(CLMARCH_CHANNEL_DIFFUSE, layers.diffuse.x);
  STORE_PLANE(CLMARCH_CHANNEL_DIFFUSE + 1, layers.diffuse.y);
  STORE_PLANE(CLMARCH_CHANNEL_DIFFUSE + 2, layers.diffuse.z);
  STORE_PLANE(CLMARCH_CHANNEL_SPECULAR, layers.specular.x);
  STORE_PLANE(CLMARCH_CHANNEL_SPECULAR + 1, layers.specular.y);
  STORE_PLANE(CLMARCH_CHANNEL_SPECULAR + 2, layers.specular.z);
#endif
#else
  if (LANE_ANY(m->hit)) {
    normal = v3_select(normal, estimate_normal(values, m->local_point, params->normal_epsilon), m->hit);
#if defined(WRITE_IDS)
    vec3v albedo, surface, emission;
    vfloat hit_id;
    map_color(values, m->local_point, &albedo, &surface, &emission, &hit_id);
    id = select(id, hit_id, m->hit);
#endif
  }
#endif
#if defined(WRITE_IDS)
  STORE_PLANE(CLMARCH_CHANNEL_ID, id);
#else
  (void)id;
#endif
#if defined(WRITE_NORMALS)
  STORE_PLANE(CLMARCH_CHANNEL_NX, normal.x);
  STORE_PLANE(CLMARCH_CHANNEL_NY, normal.y);
  STORE_PLANE(CLMARCH_CHANNEL_NZ, normal.z);
#else
  (void)normal; /* a color image alone: three planes fewer to write (a quarter of the torus's frame) */
#endif
#ifdef NEED_SHADING
  STORE_PLANE(CLMARCH_CHANNEL_R, color.x);
  STORE_PLANE(CLMARCH_CHANNEL_G, color.y);
  STORE_PLANE(CLMARCH_CHANNEL_B, color.z);
#endif
#endif
#undef STORE_PLANE
  (void)lights;
}

#if defined(ANTIALIAS)
#if LANES == 1
#define LOAD_PRIVATE(a) ((a)[0])
#else
#define LOAD_PRIVATE(a) VLOAD_LANES(0, (a))
#endif

/* A refining pass's packet number `packet` (params->sampling.x = 1): the (pixel, sample) pairs
 * packet * LANES .. packet * LANES + LANES - 1, a pair a lane, of samples 1 .. N - 1 (N =
 * params->sampling.y) of each of the pass's params->sampling.z pixels in turn: pair f is sample
 * 1 + f % (N - 1) of pixel pixels[f / (N - 1)] (its index in the rows from params->first_row on).
 * sample_points holds the samples' x, then from CLMARCH_SAMPLE_POINT_STRIDE their y, in pixel
 * units from its top-left corner. A pixel's samples are as coherent as rays get, and every lane
 * has one, where a packet of neighbouring pixels marched once a sample left most lanes idle along
 * the edges it refines. The tile test and the cones are made for the centre rays; these are off
 * them. */
SDF_INLINE Packet sample_packet(const MarchParams* params, int packet, __global const int* pixels,
                                __constant float* sample_points) {
  const int per_pixel = (int)params->sampling.y - 1;
  const int pairs = (int)params->sampling.z * per_pixel;
  real x[LANES], y[LANES];
  mask1 live[LANES];
  /* Divisions once a pixel, not once a lane: they were most of a sample's cost where rays miss. */
  const int first = packet * LANES;
  int pixel_at = first / per_pixel;
  int sample = 1 + first - pixel_at * per_pixel;
  int pixel_x = 0, pixel_y = 0;
  int located = -1;
  for (int lane = 0; lane < LANES; ++lane) {
    const int in_range = first + lane < pairs;
    if (in_range && located != pixel_at) {
      const int pixel = pixels[pixel_at];
      const int row = pixel / params->width;
      pixel_x = pixel - row * params->width;
      pixel_y = params->first_row + row;
      located = pixel_at;
    }
    x[lane] = (real)pixel_x + (in_range ? sample_points[sample] : 0.5f);
    y[lane] = (real)pixel_y + (in_range ? sample_points[CLMARCH_SAMPLE_POINT_STRIDE + sample] : 0.5f);
    live[lane] = in_range ? -1 : 0;
    if (++sample > per_pixel) {
      sample = 1;
      ++pixel_at;
    }
  }
  Packet k;
  k.x0 = 0;
  k.row0 = 0;
  k.columns = 0;
  k.rows = 0;
  k.t_start = (vfloat)(0.0f);
  k.t_end = (vfloat)(params->max_distance);
  k.dir = camera_ray_at(params, LOAD_PRIVATE(x), LOAD_PRIVATE(y));
  k.marching = LOAD_PRIVATE(live);
  clip_to_bounds(params, k.dir, &k.marching, &k.t_start, &k.t_end);
  return k;
}

#if defined(WRITE_LAYERS)
#define REFINED_FLOAT4S CLMARCH_REFINED_FLOAT4S(1)
#else
#define REFINED_FLOAT4S CLMARCH_REFINED_FLOAT4S(0)
#endif

/* Writes what a sample packet's march found: for each pixel whose pairs it holds, the sum of their
 * tone-mapped colors (programs without shading: 0) and how many of them hit, then with
 * WRITE_LAYERS the sums of their layers, as REFINED_FLOAT4S float4s from the first of those pairs'
 * slot (a pair that starts the packet or its pixel's samples); the other pairs' slots are left
 * alone: the host adds about one slot a packet instead of one a sample. */
SDF_INLINE void store_samples(SceneValues values, const Packet* k, const MarchResult* m, const MarchParams* params,
                              __global const LightParams* lights, int packet, __global float4* samples) {
  const int pairs = (int)params->sampling.z * ((int)params->sampling.y - 1);
  /* Per lane: r, g, b, hit, then the layers' r, g, b, a float4 each */
  float lane_sums[REFINED_FLOAT4S * 4][LANES];
#ifdef NEED_SHADING
  vec3v normal;
  vfloat id;
  LightTerms layers;
  const vec3v color = packet_color(values, k, m, params, lights, &normal, &id, &layers);
  STORE_LANES(color.x, 0, lane_sums[0]);
  STORE_LANES(color.y, 0, lane_sums[1]);
  STORE_LANES(color.z, 0, lane_sums[2]);
#if defined(WRITE_LAYERS)
  const vec3v terms[3] = {layers.ambient, layers.diffuse, layers.specular};
  for (int t = 0; t < 3; ++t) {
    STORE_LANES(terms[t].x, 0, lane_sums[4 + 4 * t]);
    STORE_LANES(terms[t].y, 0, lane_sums[5 + 4 * t]);
    STORE_LANES(terms[t].z, 0, lane_sums[6 + 4 * t]);
    STORE_LANES((vfloat)(0.0f), 0, lane_sums[7 + 4 * t]);
  }
#endif
#else
  (void)values;
  (void)lights;
  for (int c = 0; c < 3; ++c) STORE_LANES((vfloat)(0.0f), 0, lane_sums[c]);
#endif
  STORE_LANES(select((vfloat)(0.0f), (vfloat)(1.0f), m->hit), 0, lane_sums[3]);
  const int per_pixel = (int)params->sampling.y - 1;
  const int first = packet * LANES;
  int to_pixel_end = per_pixel - first % per_pixel; /* pairs left of the first lane's pixel */
  float4 sum[REFINED_FLOAT4S];
  for (int s = 0; s < REFINED_FLOAT4S; ++s) sum[s] = (float4)(0.0f);
  int run_start = first;
  for (int lane = 0; lane < LANES && first + lane < pairs; ++lane) {
    if (to_pixel_end == 0) {
      for (int s = 0; s < REFINED_FLOAT4S; ++s) {
        samples[run_start * REFINED_FLOAT4S + s] = sum[s];
        sum[s] = (float4)(0.0f);
      }
      run_start = first + lane;
      to_pixel_end = per_pixel;
    }
    for (int s = 0; s < REFINED_FLOAT4S; ++s) {
      sum[s] += (float4)(lane_sums[4 * s][lane], lane_sums[4 * s + 1][lane], lane_sums[4 * s + 2][lane],
                         lane_sums[4 * s + 3][lane]);
    }
    --to_pixel_end;
  }
  if (run_start < pairs) {
    for (int s = 0; s < REFINED_FLOAT4S; ++s) samples[run_start * REFINED_FLOAT4S + s] = sum[s];
  }
}

/* A refining pass's work-item: sample packets item and item + 1 (PACKETS_PER_ITEM = 2, marched
 * interleaved, as on the centre pass) or item, their sums into samples (store_samples). */
SDF_INLINE void refine_item(const MarchParams* params, vec3v origin, __global const LightParams* lights,
                            SceneValues values, int item, __global const int* pixels, __constant float* sample_points,
                            __global float4* samples) {
  const MarchRecord record = {0};
  const int pairs = (int)params->sampling.z * ((int)params->sampling.y - 1);
  if (item * LANES >= pairs) return; /* padding of the dispatch to whole work-groups */
  const Packet a = sample_packet(params, item, pixels, sample_points);
#if PACKETS_PER_ITEM == 2
  /* Past the pairs b has no lane marching, and its loop never runs. */
  const Packet b = sample_packet(params, item + 1, pixels, sample_points);
  PlainMarch march_a =
      plain_march_begin(origin, a.dir, a.marching, a.t_start, a.t_end, camera_limits(values, params, &a, &record));
  PlainMarch march_b =
      plain_march_begin(origin, b.dir, b.marching, b.t_start, b.t_end, camera_limits(values, params, &b, &record));
  march_plain_pair(&march_a, &march_b);
  const MarchResult ma = plain_march_end(&march_a);
  store_samples(values, &a, &ma, params, lights, item, samples);
  if ((item + 1) * LANES < pairs) {
    const MarchResult mb = plain_march_end(&march_b);
    store_samples(values, &b, &mb, params, lights, item + 1, samples);
  }
#else
  const MarchResult m =
      MARCH(origin, a.dir, a.marching, a.t_start, a.t_end, camera_limits(values, params, &a, &record));
  store_samples(values, &a, &m, params, lights, item, samples);
#endif
}
#endif

/* Each work-item marches PACKETS_PER_ITEM consecutive packets of the chunk: two on CPUs, whose
 * steps interleave (march_plain_pair), one on GPUs and under the cells tiling. values holds the
 * scene's numbers that the program reads instead of spelling them (an animation's; NULL when it
 * spells them all). */
__kernel void march(const MarchParams params, __global float* out, __global const LightParams* lights,
                    SceneValues values
#if defined(COARSE_PASS)
                    ,
                    __global const float* coarse_starts
#endif
#if defined(ANTIALIAS)
                    ,
                    __global const int* refine_pixels, __constant float* sample_points, __global float4* refined_samples
#endif
#if defined(RECORD_SAMPLES)
                    ,
                    __global const int* sample_base, __global float* samples, const int sample_stride
#endif
) {
#if defined(RECORD_SAMPLES)
  const MarchRecord record = {sample_base, samples, sample_stride};
#else
  const MarchRecord record = {0};
#endif
  const vec3v origin = camera_origin(&params);
#if !defined(COARSE_PASS)
  __global const float* coarse_starts = 0;
#endif
  const int item = (int)get_global_id(0) * PACKETS_PER_ITEM;
#if defined(ANTIALIAS)
  /* A refining pass runs over the samples of the host's list of pixels, not over the chunk's tiles. */
  if (params.sampling.x != 0.0f) {
    refine_item(&params, origin, lights, values, item, refine_pixels, sample_points, refined_samples);
    return;
  }
#endif
  Packet a = packet_at(&params, item, coarse_starts);
  if (a.rows <= 0) return; /* padding of the dispatch to whole work-groups */
#if PACKETS_PER_ITEM == 2
  Packet b = packet_at(&params, item + 1, coarse_starts);
  const int b_wanted = b.rows > 0;
  PlainMarch march_a =
      plain_march_begin(origin, a.dir, a.marching, a.t_start, a.t_end, camera_limits(values, &params, &a, &record));
  /* Past the chunk b has no lane marching, and its loop never runs. */
  PlainMarch march_b =
      plain_march_begin(origin, b.dir, b.marching, b.t_start, b.t_end, camera_limits(values, &params, &b, &record));
  march_plain_pair(&march_a, &march_b);
  const MarchResult ma = plain_march_end(&march_a);
  finish_packet(values, &a, &ma, &params, out, lights);
  if (b_wanted) {
    const MarchResult mb = plain_march_end(&march_b);
    finish_packet(values, &b, &mb, &params, out, lights);
  }
#else
  const MarchResult m =
      MARCH(origin, a.dir, a.marching, a.t_start, a.t_end, camera_limits(values, &params, &a, &record));
  finish_packet(values, &a, &m, &params, out, lights);
#endif
}
