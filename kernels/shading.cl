/* Direct lighting of a surface point: Lambert diffuse with Phong or Blinn-Phong specular, or a
 * PBR material (Cook-Torrance: GGX distribution, Smith-Schlick geometry, Fresnel-Schlick) with
 * metallic and roughness; the point, directional and spot lights of a global buffer (as many as 1024 pass constant
 * memory), with falloff and range (SHAPED_LIGHTS); hard or soft shadows by marching towards each light that casts them
 * (SHADOW_MODE); ambient occlusion by marching along the normal (AMBIENT_OCCLUSION) and from the step count (STEP_AO).
 * The numbers are MarchParams.shading's (kernels/device_types.h). Light positions are relative to the camera, so
 * lighting keeps its precision far from the origin; shadow and occlusion rays run in the frame of map(), like the
 * camera ray. */

/* The surface where a ray hit. */
typedef struct {
  vec3v point;    /* in map()'s frame */
  vec3v relative; /* relative to the camera, for the lights */
  vec3v normal;
  vec3v albedo;
  vec3v surface; /* PBR: x = metallic, y = roughness; the other models: x = specular, y = shininess; z = reflectivity */
  vec3v emission; /* light the surface emits, added unlit (EMISSION) */
  vfloat steps;
#if defined(WRITE_IDS)
  vfloat id; /* the number of the primitive hit */
#endif
} Hit;

SDF_INLINE vec3v point_light_direction(vec3v p, float4 position) { return v3_normalize(v3_sub(v3_from(position), p)); }

#if defined(SHADOW_MODE)
#if SHADOW_MODE == CLMARCH_SHADOW_SOFT && !defined(TILING_CELLS)
/* How fast a ray from the camera-relative point relative along l moves away from the scene's
 * bounds once it has left them, per unit of t and in units of the field: outside them the field is
 * at least the distance to them over their gain (MarchParams.bounds_gain), and that distance grows
 * at least as fast as the distance to the plane the ray leaves by: the box's face (|l| along its
 * axis) or the sphere's tangent plane (the cosine of l with the sphere's normal there). */
SDF_INLINE vfloat exit_slope(const MarchParams* params, vec3v relative, vec3v l) {
  vfloat slope = (vfloat)(0.0f), sphere_exit = (vfloat)(INFINITY);
  if (params->bounds.w > 0.0f) {
    const vec3v offset = v3_add(relative, v3_from(params->bounds));
    const vfloat b = v3_dot(offset, l);
    const vec3v closest = v3_sub(offset, v3_scale(l, b));
    const vfloat root = sqrt(fmax(params->bounds.w * params->bounds.w - v3_dot(closest, closest), 0.0f));
    sphere_exit = root - b;
    slope = root / (params->bounds.w * params->bounds_gain.x);
  }
  if (params->box_low.w > 0.0f) {
    const vec3v low = v3_sub(v3_from(params->box_low), relative), high = v3_sub(v3_from(params->box_high), relative);
    const vfloat far_x = select(fmax(low.x / l.x, high.x / l.x), (vfloat)(INFINITY), MASK(l.x == 0.0f));
    const vfloat far_y = select(fmax(low.y / l.y, high.y / l.y), (vfloat)(INFINITY), MASK(l.y == 0.0f));
    const vfloat far_z = select(fmax(low.z / l.z, high.z / l.z), (vfloat)(INFINITY), MASK(l.z == 0.0f));
    const vfloat box_exit = fmin(far_x, fmin(far_y, far_z));
    const vfloat across = fmax(select((vfloat)(0.0f), fabs(l.x), MASK(far_x == box_exit)),
                               fmax(select((vfloat)(0.0f), fabs(l.y), MASK(far_y == box_exit)),
                                    select((vfloat)(0.0f), fabs(l.z), MASK(far_z == box_exit))));
    slope = select(slope, across / params->bounds_gain.y, MASK(box_exit <= sphere_exit));
  }
  return slope;
}

/* A soft shadow's ray that the scene's bounds cut at t_exit short of t_end goes on for as long as
 * its later samples could still lower its penumbra P: past t_exit, k h / t >= k c (t - t_exit) / t
 * (c: exit_slope), which reaches P at t = t_exit k c / (k c - P). It resumes at m.t, the sample the
 * cut ray did not take, so its samples, and its penumbra, are the uncut ray's. */
SDF_INLINE MarchResult march_past_bounds(MarchResult m, vec3v origin, vec3v relative, vec3v l, vint live, vfloat t_exit,
                                         vfloat t_end, const MarchParams* params, MarchLimits limits) {
  const vfloat kc = limits.soft_k * exit_slope(params, relative, l);
  const vfloat t_stop = fmin(select(t_end, t_exit * kc / (kc - m.penumbra), MASK(kc > m.penumbra)), t_end);
  const float budget = (float)limits.max_steps;
  const vint going_on = live & ~m.hit & MASK(t_exit < t_end) & MASK(m.t < t_stop) & MASK(m.steps < budget);
  if (!LANE_ANY(going_on)) return m;
  PlainMarch s = plain_march_begin(origin, l, going_on, m.t, t_stop, limits);
  s.m.steps = m.steps;
  s.m.penumbra = m.penumbra;
  for (int step = 0; step < limits.max_steps && LANE_ANY(s.active); ++step) {
    plain_march_step(&s);
    s.active &= MASK(s.m.steps < budget);
  }
  const MarchResult resumed = plain_march_end(&s);
  m.hit |= going_on & resumed.hit;
  m.penumbra = select(m.penumbra, resumed.penumbra, going_on);
  return m;
}
#endif

/* Light reaching p (relative: p relative to the camera) from unit direction l over distance t_end:
 * 0 behind an occluder, 1 unlit by none, the penumbra in between for soft shadows. Hard shadows'
 * rays march inside the scene's bounds only: past them the light is unoccluded. Soft ones go on
 * past them as far as their penumbra could still fall (march_past_bounds); the improved variant's
 * estimate has no such floor, and its rays march to t_end. */
SDF_STAGE vfloat shadow_factor(SceneValues values, const MarchParams* params, vec3v p, vec3v relative, vec3v n, vec3v l,
                               vfloat t_end, vint live) {
  const ShadingParams* shading = &params->shading;
  MarchLimits limits = {values, shading->shadow_max_steps, params->epsilon, SHADOW_MODE, shading->shadow_k, 1.0f,
                        0.0f,   params->cell_bounds};
  /* Leave the surface along its normal first so the ray does not hit its own start. */
  const vec3v origin = v3_add(p, v3_scale(n, params->epsilon * 4.0f));
  vfloat t_start = (vfloat)(shading->shadow_min_t), t_exit = t_end;
  vint marching = live;
#if SHADOW_MODE != CLMARCH_SHADOW_SOFT_IMPROVED
  clip_to_scene_bounds(params, relative, l, 1, &marching, &t_start, &t_exit);
#endif
  MarchResult m = MARCH(origin, l, marching, t_start, t_exit, limits);
#if SHADOW_MODE == CLMARCH_SHADOW_SOFT && !defined(TILING_CELLS)
  m = march_past_bounds(m, origin, relative, l, live, t_exit, t_end, params, limits);
#endif
  const vfloat lit = SHADOW_MODE == CLMARCH_SHADOW_HARD ? (vfloat)(1.0f) : clamp(m.penumbra, 0.0f, 1.0f);
  return select(lit, (vfloat)(0.0f), m.hit);
}
#endif

#if defined(AMBIENT_OCCLUSION)
/* The PBR-course occlusion: from 1, subtract (i delta - sdf(p + n i delta))^2 / i over the samples,
 * then raise to the power ao_power. */
SDF_STAGE vfloat normal_occlusion(SceneValues values, const ShadingParams* shading, vec3v p, vec3v n) {
  vfloat occlusion = (vfloat)(1.0f);
  for (int i = shading->ao_samples; i > 0; --i) {
    const float along = (float)i * shading->ao_step;
    const vfloat gap = along - field_tap(values, v3_add(p, v3_scale(n, along)));
    occlusion -= gap * gap / (float)i;
  }
  return pow(clamp(occlusion, 0.0f, 1.0f), (vfloat)(shading->ao_power));
}
#endif

/* One light's reflection off a surface, before its radiance and shadow. */
typedef struct {
  vec3v diffuse;
  vec3v specular;
} Reflection;

#if defined(SHADING_MODEL_PBR)
/* Cook-Torrance reflectance times n.l for one light: the diffuse lobe and the specular one. */
SDF_INLINE Reflection pbr_light(vec3v n, vec3v l, vec3v v, vec3v albedo, vfloat metallic, vfloat roughness) {
  const vec3v h = v3_normalize(v3_add(l, v));
  const vfloat n_dot_l = fmax(v3_dot(n, l), 0.0f);
  const vfloat n_dot_v = fmax(v3_dot(n, v), 0.0f);
  const vfloat n_dot_h = fmax(v3_dot(n, h), 0.0f);
  const vfloat h_dot_v = fmax(v3_dot(h, v), 0.0f);
  const vfloat a = roughness * roughness;
  const vfloat a2 = a * a;
  /* (n.h)^2 (a^2 - 1) + 1 as (1 - (n.h)^2) + a^2 (n.h)^2, with 1 - (n.h)^2 = |n x h|^2 for unit
   * vectors: the difference 1 - (n.h)^2 keeps none of float's digits where n.h is within a^2
   * of 1, the peak of a low roughness (a^2 = 1.6e-7 at roughness 0.02: its highlight came out
   * off by a factor of order 1). */
  const vec3v n_cross_h = v3_cross(n, h);
  const vfloat sin2 = select((vfloat)(1.0f), v3_dot(n_cross_h, n_cross_h), MASK(n_dot_h > 0.0f));
  const vfloat denom = sin2 + a2 * n_dot_h * n_dot_h;
  const vfloat distribution = a2 / (M_PI_F * denom * denom);
  const vfloat k = (roughness + 1.0f) * (roughness + 1.0f) / 8.0f;
  const vfloat geometry = n_dot_v / (n_dot_v * (1.0f - k) + k) * n_dot_l / (n_dot_l * (1.0f - k) + k);
  const vec3v f0 = v3_mix(v3_splat(0.04f), albedo, metallic);
  const vfloat schlick = pow(1.0f - h_dot_v, (vfloat)(5.0f));
  const vec3v fresnel = v3_add(f0, v3_scale(v3_sub(v3_splat(1.0f), f0), schlick));
  const vfloat specular = distribution * geometry / (4.0f * n_dot_v * n_dot_l + 1e-4f);
  const vec3v diffuse_weight = v3_scale(v3_sub(v3_splat(1.0f), fresnel), 1.0f - metallic);
  const vec3v diffuse = v3_scale(v3_mul(diffuse_weight, albedo), M_1_PI_F);
  const Reflection r = {v3_scale(diffuse, n_dot_l), v3_scale(v3_scale(fresnel, specular), n_dot_l)};
  return r;
}
#else
/* x^shininess for x >= 0, as exp2(s log2 x): PoCL 3.1's double16 pow() returns inf for some
 * lanes on AVX-512 CPUs (seen on tiled_spheres with DOUBLE_PRECISION), while exp2 and log2 are
 * right; x = 0 gives exp2(-inf) = 0. */
SDF_INLINE vfloat specular_power(vfloat shininess, vfloat x) { return exp2(shininess * log2(x)); }

/* The specular model's term for the hit's shininess. */
SDF_INLINE vfloat specular_term(vfloat shininess, vec3v n, vec3v l, vec3v v) {
#if defined(SHADING_MODEL_PHONG)
  /* reflect(-l, n) = 2 dot(n, l) n - l */
  vec3v r = v3_sub(v3_scale(n, 2.0f * v3_dot(n, l)), l);
  return specular_power(shininess, fmax(v3_dot(r, v), 0.0f));
#elif defined(SHADING_MODEL_BLINN_PHONG)
  vec3v half_vector = v3_normalize(v3_add(l, v));
  return specular_power(shininess, fmax(v3_dot(n, half_vector), 0.0f));
#else
  (void)shininess;
  (void)n;
  (void)l;
  (void)v;
  return (vfloat)(0.0f);
#endif
}

/* Lambert, and the specular model where n.l > 0, for one light; the hit's surface holds its
 * specular weight and shininess. */
SDF_INLINE Reflection classic_light(const ShadingParams* shading, vec3v n, vec3v l, vec3v v, vec3v albedo,
                                    vec3v surface) {
  const vfloat n_dot_l = fmax(v3_dot(n, l), 0.0f);
  const vfloat specular = select((vfloat)(0.0f), specular_term(surface.y, n, l, v), MASK(n_dot_l > 0.0f));
  const vfloat white = surface.x * specular;
  const Reflection r = {v3_scale(albedo, shading->diffuse * n_dot_l), v3(white, white, white)};
  return r;
}
#endif

/* Darkens by steps^2 / step_ao: many steps mean the ray crept past nearby geometry. */
SDF_INLINE vec3v apply_step_ao(const ShadingParams* shading, vec3v color, vfloat steps) {
#ifdef STEP_AO
  vfloat darkening = steps * steps / shading->step_ao;
  return v3(color.x - darkening, color.y - darkening, color.z - darkening);
#else
  (void)shading;
  (void)steps;
  return color;
#endif
}

/* The terms of the lit color (the --buffers layers ao, diffuse and specular): the ambient light the
 * occlusion leaves, and the lights' diffuse and specular reflection with their shadows. */
typedef struct {
  vec3v ambient;
  vec3v diffuse;
  vec3v specular;
} LightTerms;

#if defined(SHAPED_LIGHTS)
/* The share of a point or spot light's radiance that reaches a point d away in direction l (unit,
 * towards the light): 1 / d^2 with the inverse-square falloff, times the range's window
 * clamp(1 - (d / range)^4, 0, 1)^2, times a spot's cone: smoothstep from its outer angle (0) to its
 * inner one (1). Directional lights: 1. */
SDF_INLINE vfloat light_reach(__global const LightParams* light, vec3v l, vfloat d) {
  vfloat reach = (vfloat)(1.0f);
  if (light->kind == CLMARCH_LIGHT_DIRECTIONAL) return reach;
  if (light->falloff == CLMARCH_FALLOFF_INVERSE_SQUARE) reach = 1.0f / (d * d);
  if (light->inverse_range2 > 0.0f) {
    const vfloat q = d * d * light->inverse_range2;
    const vfloat window = clamp(1.0f - q * q, 0.0f, 1.0f);
    reach *= window * window;
  }
  if (light->kind == CLMARCH_LIGHT_SPOT) {
    /* The cosine of the angle between the spot's axis and its ray to the point, -l. */
    const float4 axis = light->spot_axis;
    const vfloat c = -(l.x * axis.x + l.y * axis.y + l.z * axis.z);
    const vfloat s = clamp((c - light->cos_outer) / fmax(light->cos_inner - light->cos_outer, 1e-7f), 0.0f, 1.0f);
    reach *= s * s * (3.0f - 2.0f * s);
  }
  return reach;
}
#endif

/* The terms of the surface's lit color, seen along -view (unit). */
SDF_INLINE LightTerms light_terms(SceneValues values, const MarchParams* params, const Hit* hit, vec3v view, vint live,
                                  __global const LightParams* lights) {
  const ShadingParams* shading = &params->shading;
  vfloat ambient_occlusion = (vfloat)(1.0f);
#if defined(AMBIENT_OCCLUSION)
  ambient_occlusion = normal_occlusion(values, shading, hit->point, hit->normal);
#endif
  LightTerms terms;
  terms.ambient = v3_scale(v3_mul(hit->albedo, v3_from(shading->ambient)), ambient_occlusion);
#if defined(EMISSION)
  /* Emitted light is unlit: the ambient layer carries it. */
  terms.ambient = v3_add(terms.ambient, hit->emission);
#endif
  terms.diffuse = v3_splat(0.0f);
  terms.specular = v3_splat(0.0f);
  for (int k = 0; k < shading->light_count; ++k) {
    const float4 where = lights[k].where;
    const float4 radiance = lights[k].radiance;
    const bool positional = lights[k].kind != CLMARCH_LIGHT_DIRECTIONAL;
    const vec3v l = positional ? point_light_direction(hit->relative, where) : v3_from(where);
    /* How far the light is; directional lights' shadow rays end at shadow_max_t. */
    const vfloat distance =
        positional ? v3_length(v3_sub(v3_from(where), hit->relative)) : (vfloat)(shading->shadow_max_t);
#if defined(SHADING_MODEL_PBR)
    const Reflection lit = pbr_light(hit->normal, l, view, hit->albedo, hit->surface.x, hit->surface.y);
#else
    const Reflection lit = classic_light(shading, hit->normal, l, view, hit->albedo, hit->surface);
#endif
    vec3v reaching = v3_from(radiance);
#if defined(SHAPED_LIGHTS)
    reaching = v3_scale(reaching, light_reach(&lights[k], l, distance));
#endif
#if defined(SHADOW_MODE)
    if (lights[k].casts_shadows) {
      reaching = v3_scale(reaching, shadow_factor(values, params, hit->point, hit->relative, hit->normal, l, distance,
                                                  live & MASK(v3_dot(hit->normal, l) > 0.0f)));
    }
#else
    (void)live;
    (void)distance;
#endif
    terms.diffuse = v3_add(terms.diffuse, v3_mul(lit.diffuse, reaching));
    terms.specular = v3_add(terms.specular, v3_mul(lit.specular, reaching));
  }
  return terms;
}

/* The lit color of a hit whose march took steps: its terms, darkened by the step count. */
SDF_INLINE vec3v lit_color(const ShadingParams* shading, const LightTerms* terms, vfloat steps) {
  const vec3v color = v3_add(v3_add(terms->ambient, terms->diffuse), terms->specular);
  return v3_max0(apply_step_ao(shading, color, steps));
}

/* Lit color of the surface, seen along -view (unit). */
SDF_STAGE vec3v shade(SceneValues values, const MarchParams* params, const Hit* hit, vec3v view, vint live,
                      __global const LightParams* lights) {
  const LightTerms terms = light_terms(values, params, hit, view, live, lights);
  return lit_color(&params->shading, &terms, hit->steps);
}
