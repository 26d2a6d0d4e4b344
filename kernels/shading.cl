/* Direct lighting: Lambert diffuse plus Phong or Blinn-Phong specular (SHADING_MODEL_PHONG,
 * SHADING_MODEL_BLINN_PHONG), with the constants SHADING_DIFFUSE, SHADING_SPECULAR,
 * SHADING_SHININESS and AMBIENT_COLOR, LIGHT_COUNT lights from a constant buffer, the step-count
 * ambient occlusion of the Crum article (SHADING_STEP_AO) and Beer-Lambert fog (FOG_DENSITY,
 * FOG_COLOR). Positions are relative to the camera, so lighting keeps its precision far from the
 * origin. */

SDF_INLINE vec3v point_light_direction(vec3v p, float4 position) { return v3_normalize(v3_sub(v3_from(position), p)); }

SDF_INLINE vfloat specular_term(vec3v n, vec3v l, vec3v v) {
#if defined(SHADING_MODEL_PHONG)
  /* reflect(-l, n) = 2 dot(n, l) n - l */
  vec3v r = v3_sub(v3_scale(n, 2.0f * v3_dot(n, l)), l);
  return pow(fmax(v3_dot(r, v), 0.0f), (vfloat)(SHADING_SHININESS));
#elif defined(SHADING_MODEL_BLINN_PHONG)
  vec3v half_vector = v3_normalize(v3_add(l, v));
  return pow(fmax(v3_dot(n, half_vector), 0.0f), (vfloat)(SHADING_SHININESS));
#else
  (void)n;
  (void)l;
  (void)v;
  return (vfloat)(0.0f);
#endif
}

/* Adds one light of the given radiance (color * intensity) arriving from unit direction l. */
SDF_INLINE vec3v add_light(vec3v color, vec3v albedo, vec3v n, vec3v l, vec3v v, float4 radiance) {
  vfloat n_dot_l = fmax(v3_dot(n, l), 0.0f);
  vec3v lit = v3_mul(albedo, v3_scale(v3_from(radiance), SHADING_DIFFUSE * n_dot_l));
  vfloat specular = select((vfloat)(0.0f), specular_term(n, l, v), MASK(n_dot_l > 0.0f));
  lit = v3_add(lit, v3_scale(v3_from(radiance), SHADING_SPECULAR * specular));
  return v3_add(color, lit);
}

/* Darkens by steps^2 / SHADING_STEP_AO: many steps mean the ray crept past nearby geometry. */
SDF_INLINE vec3v apply_step_ao(vec3v color, vfloat steps) {
#ifdef SHADING_STEP_AO
  vfloat darkening = steps * steps / SHADING_STEP_AO;
  return v3(color.x - darkening, color.y - darkening, color.z - darkening);
#else
  (void)steps;
  return color;
#endif
}

/* Lit color at p_rel (the hit point relative to the camera, at depth t) with unit normal n, seen
 * along -view. Each light is (xyz position relative to the camera, w = 1) or (xyz unit direction
 * towards the light, w = 0), then its radiance. */
SDF_INLINE vec3v shade(vec3v p_rel, vfloat t, vec3v n, vec3v view, vfloat steps, vec3v albedo, __constant float4* lights) {
  vec3v color = v3_mul(albedo, v3_from(AMBIENT_COLOR));
  for (int k = 0; k < LIGHT_COUNT; ++k) {
    const float4 where = lights[CLMARCH_LIGHT_FLOAT4S * k];
    const vec3v l = where.w > 0.5f ? point_light_direction(p_rel, where) : v3_from(where);
    color = add_light(color, albedo, n, l, view, lights[CLMARCH_LIGHT_FLOAT4S * k + 1]);
  }
  color = v3_max0(apply_step_ao(color, steps));
#ifdef FOG_DENSITY
  color = v3_mix(v3_from(FOG_COLOR), color, exp(-FOG_DENSITY * t));
#else
  (void)t;
#endif
  return color;
}
