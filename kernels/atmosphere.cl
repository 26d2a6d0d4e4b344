/* What the camera sees besides lit surfaces: the sky of misses (the background, or with SKY a
 * gradient from horizon to zenith by the ray's height), Crum's glow of misses from their closest
 * approach (GLOW), a planetary glow at the horizon (PLANET_GLOW), fog on hits (Beer-Lambert FOG,
 * Inigo Quilez's HEIGHT_FOG), and the HDR tone mapping and gamma of the PBR course
 * (TONE_MAP_REINHARD, DISPLAY_GAMMA). The numbers are MarchParams.shading's. */

SDF_INLINE vec3v sky_color(const ShadingParams* shading, vec3v dir) {
#if defined(SKY)
  const vfloat up = clamp(dir.y, 0.0f, 1.0f);
  vec3v sky = v3_mix(v3_from(shading->sky_horizon), v3_from(shading->sky_zenith), up);
#else
  vec3v sky = v3_from(shading->background);
#endif
#if defined(PLANET_GLOW)
  /* Scattering piles up where the view grazes the atmosphere (the horizon) and towards the sun. */
  const float4 sun = shading->planet_glow_sun;
  const vfloat towards_sun = fmax(dir.x * sun.x + dir.y * sun.y + dir.z * sun.z, 0.0f);
  const vfloat sun_term = 1.0f + pow(towards_sun, (vfloat)(8.0f));
  const vfloat glow = exp(-shading->planet_glow_sharpness * fabs(dir.y)) * sun_term;
  sky = v3_add(sky, v3_scale(v3_from(shading->planet_glow_color), glow));
#endif
  return sky;
}

/* A miss: the sky, plus Crum's glow where the ray passed close to the surface. */
SDF_INLINE vec3v miss_color(const ShadingParams* shading, vec3v dir, vfloat closest) {
  vec3v color = sky_color(shading, dir);
#if defined(GLOW)
  const vfloat near = clamp(1.0f - closest / shading->glow_radius, 0.0f, 1.0f);
  color = v3_add(color, v3_scale(v3_from(shading->glow_color), near * near));
#else
  (void)closest;
#endif
  return color;
}

/* Fog over depth t along dir from a camera at height camera_y. */
SDF_INLINE vec3v apply_fog(const ShadingParams* shading, vec3v color, vec3v dir, vfloat t, float camera_y) {
#if defined(FOG)
  color = v3_mix(v3_from(shading->fog_color), color, exp(-shading->fog_density * t));
#endif
#if defined(HEIGHT_FOG)
  /* (a / b) exp(-y0 b) (1 - exp(-x)) / dy with x = t dy b, whose limit for a level ray is
   * a exp(-y0 b) t. 1 - exp(-x) is -expm1(-x), which keeps float's digits where x is small (a
   * small falloff); a descending ray (x < 0) takes exp(-y0 b - x) expm1(x) instead, the density
   * where it ends, as exp(-x) overflows float from x < -88 (a high camera looking down). */
  const float a = shading->height_fog_density, b = shading->height_fog_falloff;
  const vint level = MASK(fabs(dir.y) < 1e-5f);
  const vfloat x = t * dir.y * b;
  const vint descending = MASK(x < 0.0f);
  const vfloat start = exp(select((vfloat)(-camera_y * b), -camera_y * b - x, descending));
  const vfloat slanted =
      (a / b) * start * select(-expm1(-x), expm1(x), descending) / select(dir.y, (vfloat)(1.0f), level);
  const vfloat amount = clamp(select(slanted, a * exp(-camera_y * b) * t, level), 0.0f, 1.0f);
  const float4 sun = shading->height_fog_sun_direction;
  const vfloat sun_amount = fmax(dir.x * sun.x + dir.y * sun.y + dir.z * sun.z, 0.0f);
  const vec3v fog = v3_mix(v3_from(shading->height_fog_color), v3_from(shading->height_fog_sun_color),
                           pow(sun_amount, (vfloat)(shading->height_fog_sun_power)));
  color = v3_mix(color, fog, amount);
#else
  (void)camera_y;
#endif
  (void)shading;
  (void)dir;
  (void)t;
  return color;
}

/* HDR to display: Reinhard c / (c + 1), then c^(1 / gamma). */
SDF_INLINE vec3v tone_map(const ShadingParams* shading, vec3v color) {
#if defined(TONE_MAP_REINHARD)
  color = v3(color.x / (color.x + 1.0f), color.y / (color.y + 1.0f), color.z / (color.z + 1.0f));
#endif
#if defined(DISPLAY_GAMMA)
  const vfloat inverse = (vfloat)(1.0f / shading->gamma);
  color = v3(pow(color.x, inverse), pow(color.y, inverse), pow(color.z, inverse));
#endif
  (void)shading;
  return color;
}
