/* The plain sphere-tracing loop and the result type every march loop (tiling.cl too) returns. A
 * lane goes idle once its ray hits (distance < epsilon), passes its end or the step budget runs
 * out (both misses). The same loop serves camera rays, reflection rays and shadow rays; a shadow
 * ray also tracks Inigo Quilez's penumbra min(k h / t) (CLMARCH_SHADOW_SOFT, or
 * CLMARCH_SHADOW_SOFT_IMPROVED for his improved variant), and every ray the closest approach to the surface (for the
 * glow of misses). */

/* What the march of one packet found. */
typedef struct {
  vfloat t;          /* depth along the unit ray where it hit */
  vfloat steps;      /* every iteration: distance steps and wall steps */
  vfloat wall_steps; /* iterations that stepped to a cell wall (tiling) */
  vint hit;
  vint exhausted;    /* lanes the step budget stopped: neither hit nor past their end */
  vec3v local_point; /* the hit point in the frame map() is written in (a cell's, under tiling) */
  vfloat closest;    /* smallest distance met on the way */
  vfloat penumbra;   /* soft shadows: light reaching the start point, 1 when unoccluded */
} MarchResult;

/* Limits of one march; shadow_mode and soft_k only matter for shadow rays. Camera rays set
 * over_relaxation and hit_cone_slope; shadow and mirror rays march plainly with the fixed epsilon
 * (1 and 0). */
typedef struct {
  SceneValues values; /* the scene's animated values (map()) */
  int max_steps;
  float epsilon;
  int shadow_mode; /* CLMARCH_SHADOW_*: the penumbra a shadow ray tracks; camera and mirror rays
                      are CLMARCH_SHADOW_HARD, which tracks none */
  float soft_k;
  float over_relaxation; /* Keinert et al.'s omega; steps of omega * d while it is > 1 */
  float hit_cone_slope;  /* a lane arrives below max(epsilon, hit_cone_slope * t) */
  float4 cell_bounds;    /* the cells tiling: MarchParams.cell_bounds (kernels/tiling.cl) */
#if defined(RECORD_SAMPLES)
  /* The benchmark's record of every point the march evaluates (kernels/replay.cl): lane l writes
   * its k-th point to index sample_base[l] + k of the planes x, y, z of samples, sample_stride
   * floats apart. NULL (shadow and mirror rays) or a negative base: not recorded. */
  __global float* samples;
  int sample_stride;
  vint sample_base;
#endif
} MarchLimits;

#if defined(RECORD_SAMPLES)
/* Stores the point p of every active lane at its ray's next sample index (steps so far). */
SDF_INLINE void record_samples(const MarchLimits* limits, vec3v p, vint active, vfloat steps) {
  if (!limits->samples) return;
  real xs[LANES], ys[LANES], zs[LANES], counts[LANES];
  mask1 bases[LANES], recording[LANES];
  STORE_PRIVATE(p.x, xs);
  STORE_PRIVATE(p.y, ys);
  STORE_PRIVATE(p.z, zs);
  STORE_PRIVATE(steps, counts);
  STORE_PRIVATE(limits->sample_base, bases);
  STORE_PRIVATE(active, recording);
  for (int lane = 0; lane < LANES; ++lane) {
    if (recording[lane] == 0 || bases[lane] < 0) continue;
    const long at = (long)bases[lane] + (long)counts[lane];
    limits->samples[at] = (float)xs[lane];
    limits->samples[limits->sample_stride + at] = (float)ys[lane];
    limits->samples[2L * limits->sample_stride + at] = (float)zs[lane];
  }
}
#endif

/* The distance below which a lane at depth t has arrived: epsilon, or the pixel cone's radius, and
 * never less than REAL_EPSILON * t (2^-23 t in float, the spacing of t at most): a smaller step leaves
 * t + d == t, and the lane would stall until its budget ran out (a floor seen at grazing angles 2e4
 * away, tests/stress_settings_test.cpp). The double reference needs no floor; `clmarch check`
 * allows for it. Do not remove it. */
SDF_INLINE vfloat hit_threshold(const MarchLimits* limits, vfloat t) {
  const vfloat base =
      limits->hit_cone_slope > 0.0f ? fmax(limits->hit_cone_slope * t, limits->epsilon) : (vfloat)(limits->epsilon);
  return fmax(base, REAL_EPSILON * t);
}

/* Clips the rays offset + t dir (offset: the rays' origins less the sphere's centre; dir unit) to
 * the sphere of the given radius: t_start moves up to where a ray enters it, t_end down to where it
 * leaves, and lanes whose ray misses it or whose span is then empty stop marching. Nothing lies
 * outside the scene's bounding sphere, so camera rays and the secondary rays (shadow, mirror) all
 * march inside it alone. The discriminant is taken as r^2 - |offset - b dir|^2, which keeps its
 * precision far from the sphere. */
SDF_INLINE void clip_to_sphere(vec3v offset, float radius, vec3v dir, vint* marching, vfloat* t_start, vfloat* t_end) {
  const vfloat b = v3_dot(offset, dir);
  const vec3v closest = v3_sub(offset, v3_scale(dir, b));
  const vfloat h = radius * radius - v3_dot(closest, closest);
  const vfloat root = sqrt(fmax(h, 0.0f));
  const vint meets = MASK(h >= 0.0f);
  *t_start = select(*t_start, fmax(-b - root, *t_start), meets);
  *t_end = fmin(-b + root, *t_end);
  *marching &= meets & MASK(*t_end > *t_start);
}

/* Narrows [near, far] to where the rays are between two planes of a box, low and high along one
 * axis less the rays' origins, dir their direction along it: a ray parallel to the planes is
 * between them everywhere or nowhere. */
SDF_INLINE void clip_to_slab(vfloat low, vfloat high, vfloat dir, vfloat* near, vfloat* far) {
  const vfloat inverse = 1.0f / dir;
  const vfloat a = low * inverse, b = high * inverse;
  const vint parallel = MASK(dir == 0.0f);
  const vint between = MASK(low <= 0.0f) & MASK(high >= 0.0f);
  *near = fmax(*near, select(fmin(a, b), select((vfloat)(INFINITY), (vfloat)(-INFINITY), between), parallel));
  *far = fmin(*far, select(fmax(a, b), select((vfloat)(-INFINITY), (vfloat)(INFINITY), between), parallel));
}

/* Clips rays from the camera-relative point relative_origin along dir (unit) to what
 * MarchParams holds of the scene's bounds: the sphere (bounds) and, with_box, the box (box_low,
 * box_high), as clip_to_sphere does. The CPU reference clips camera rays the same way
 * (host/reference/reference_renderer.cpp), so their steps agree. */
SDF_INLINE void clip_to_scene_bounds(const MarchParams* params, vec3v relative_origin, vec3v dir, int with_box,
                                     vint* marching, vfloat* t_start, vfloat* t_end) {
  if (params->bounds.w > 0.0f) {
    clip_to_sphere(v3_add(relative_origin, v3_from(params->bounds)), params->bounds.w, dir, marching, t_start, t_end);
  }
  if (with_box && params->box_low.w > 0.0f) {
    const vec3v low = v3_sub(v3_from(params->box_low), relative_origin),
                high = v3_sub(v3_from(params->box_high), relative_origin);
    vfloat near = (vfloat)(-INFINITY), far = (vfloat)(INFINITY);
    clip_to_slab(low.x, high.x, dir.x, &near, &far);
    clip_to_slab(low.y, high.y, dir.y, &near, &far);
    clip_to_slab(low.z, high.z, dir.z, &near, &far);
    /* Only rays that meet both move their start: a ray that misses keeps it (the status channel). */
    const vint meets = MASK(near <= far);
    *t_start = select(*t_start, fmax(*t_start, near), *marching & meets);
    *t_end = fmin(*t_end, far);
    *marching &= meets & MASK(*t_end > *t_start);
  }
}

/* Lanes that march over-relaxed from the start: all or none (masks are -1, also for LANES 1). */
SDF_INLINE vint relaxation_mask(const MarchLimits* limits) { return (vint)(limits->over_relaxation > 1.0f ? -1 : 0); }

SDF_INLINE MarchResult march_result_init(vfloat t_start) {
  MarchResult m;
  m.t = t_start;
  m.steps = (vfloat)(0.0f);
  m.wall_steps = (vfloat)(0.0f);
  m.hit = (vint)(0);
  m.exhausted = (vint)(0);
  m.closest = (vfloat)(INFINITY);
  m.penumbra = (vfloat)(1.0f);
  return m;
}

/* Folds one distance sample h at depth t into the closest approach and the penumbra; previous is
 * the sample before (the improved variant estimates the true closest point between the two). */
SDF_INLINE void track_approach(MarchResult* m, vfloat h, vfloat previous, vint active, const MarchLimits* limits) {
  m->closest = select(m->closest, fmin(m->closest, h), active);
  if (limits->shadow_mode == CLMARCH_SHADOW_SOFT) {
    m->penumbra = select(m->penumbra, fmin(m->penumbra, limits->soft_k * h / fmax(m->t, 1e-6f)), active);
  } else if (limits->shadow_mode == CLMARCH_SHADOW_SOFT_IMPROVED) {
    const vfloat y = h * h / (2.0f * previous);
    const vfloat d = sqrt(fmax(h * h - y * y, 0.0f));
    m->penumbra = select(m->penumbra, fmin(m->penumbra, limits->soft_k * d / fmax(m->t - y, 1e-6f)), active);
  }
}

/* A plain march in progress: the result so far and what the next step needs. */
typedef struct {
  MarchResult m;
  vec3v origin, dir;
  vfloat t_end;
  vint active;     /* lanes still marching */
  vint relaxing;   /* lanes still stepping over-relaxed */
  vfloat safe;     /* where plain sphere tracing would be: the fall-back of a relaxed step */
  vfloat previous; /* the last sample's distance */
  MarchLimits limits;
} PlainMarch;

SDF_INLINE PlainMarch plain_march_begin(vec3v origin, vec3v dir, vint live, vfloat t_start, vfloat t_end,
                                        MarchLimits limits) {
  PlainMarch s;
  s.m = march_result_init(t_start);
  s.origin = origin;
  s.dir = dir;
  s.t_end = t_end;
  s.active = live;
  s.relaxing = relaxation_mask(&limits);
  s.safe = (vfloat)(INFINITY); /* nothing to undo before the first step */
  s.previous = (vfloat)(1e20f);
  s.limits = limits;
  return s;
}

/* One step of origin + t * dir for t from t_start; lanes stop at t_end (a miss).
 * Over-relaxation (Keinert et al. 2014, with the safe fall-back): a relaxing lane steps omega * d.
 * The unbounding spheres at the previous sample (radius d_prev) and at this one (radius d) cover
 * the segment between them unless t - d > t_prev + d_prev = safe, the point plain sphere tracing
 * would have reached; then the surface may have been crossed, so the sample is discarded (no hit
 * test: d may be negative inside the solid), the lane goes back to safe and marches plainly from
 * there. The test uses the signed d, so a step into the solid always falls back. */
SDF_INLINE void plain_march_step(PlainMarch* s) {
  MarchResult* m = &s->m;
  const vec3v p = v3_add(s->origin, v3_scale(s->dir, m->t));
  const vfloat d = field(s->limits.values, p);
#if defined(RECORD_SAMPLES)
  record_samples(&s->limits, p, s->active, m->steps);
#endif
  m->steps += select((vfloat)(0.0f), (vfloat)(1.0f), s->active);
  track_approach(m, d, s->previous, s->active, &s->limits);
  s->previous = d;
  /* Branches on whole packets keep plain sphere tracing (the default) as cheap as before. */
  vint undo = (vint)(0);
  if (LANE_ANY(s->relaxing)) {
    undo = s->relaxing & MASK(d < m->t - s->safe);
    s->relaxing &= ~undo;
  }
  const vint arrived = s->active & ~undo & MASK(d < hit_threshold(&s->limits, m->t));
  m->hit |= arrived;
  s->active &= ~arrived;
  vfloat next = m->t + d;
  if (LANE_ANY(s->relaxing | undo)) {
    next = select(select(next, m->t + d * s->limits.over_relaxation, s->relaxing), s->safe, undo);
    s->safe = m->t + d;
  }
  m->t = select(m->t, next, s->active);
  s->active &= MASK(m->t < s->t_end);
  s->relaxing &= s->active;
}

SDF_INLINE MarchResult plain_march_end(PlainMarch* s) {
  MarchResult m = s->m;
  m.exhausted = s->active;
  m.local_point = v3_add(s->origin, v3_scale(s->dir, m.t));
#if defined(TILING_MOD)
  m.local_point = wrap_to_cell(s->limits.values, m.local_point);
#endif
  return m;
}

/* Marches one packet: origin + t * dir for t from t_start until every lane hit, passed t_end or
 * used max_steps. */
SDF_STAGE MarchResult march_plain(vec3v origin, vec3v dir, vint live, vfloat t_start, vfloat t_end,
                                  MarchLimits limits) {
  PlainMarch s = plain_march_begin(origin, dir, live, t_start, t_end, limits);
  for (int step = 0; step < limits.max_steps && LANE_ANY(s.active); ++step) plain_march_step(&s);
  return plain_march_end(&s);
}

/* Marches two independent packets in one loop, a step of each per iteration: a march is a chain
 * of dependent steps, so the second packet's step runs while the first one's waits on its
 * latencies (square roots, the loop's branch). Each packet takes exactly the steps it would take
 * alone. */
SDF_STAGE void march_plain_pair(PlainMarch* a, PlainMarch* b) {
  /* Copies the compiler keeps in registers, which it cannot do through pointers that may alias. */
  PlainMarch first = *a, second = *b;
  for (int step = 0; step < first.limits.max_steps; ++step) {
    const int first_marching = LANE_ANY(first.active), second_marching = LANE_ANY(second.active);
    if (!(first_marching | second_marching)) break;
    if (first_marching) plain_march_step(&first);
    if (second_marching) plain_march_step(&second);
  }
  *a = first;
  *b = second;
}

#if !defined(TILING_CELLS)
/* One march, whichever tiling the scene has: origin + t * dir, origin in map()'s frame. */
#define MARCH(origin, dir, live, t_start, t_end, limits) \
  march_plain((origin), (dir), (live), (t_start), (t_end), (limits))
#endif
