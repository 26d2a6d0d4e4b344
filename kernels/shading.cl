/* Direct lighting: Lambert diffuse plus Phong or Blinn-Phong specular (SHADING_MODEL_PHONG,
 * SHADING_MODEL_BLINN_PHONG), with the constants SHADING_DIFFUSE, SHADING_SPECULAR and
 * SHADING_SHININESS, and the step-count ambient occlusion of the Crum article (SHADING_STEP_AO). */

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
