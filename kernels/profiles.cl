/* The 2D primitives: profiles in the xy plane, their distance independent of z (alone, each is a
 * prism along z without end; revolve and extrude make solids of them). Compiled in only for
 * scenes that use them; same conventions as primitives.cl (positions' z unused).
 * host/reference/reference_profiles.cpp is the independent double version. */

/* Exact. */
SDF_INLINE vfloat sd_circle(vec3v p, float4 center, float radius) {
  const vfloat x = p.x - center.x, y = p.y - center.y;
  return vsqrt(x * x + y * y) - radius;
}

/* Exact: Quilez's box in two dimensions. */
SDF_INLINE vfloat sd_rectangle(vec3v p, float4 center, float half_width, float half_height) {
  const vfloat dx = fabs(p.x - center.x) - half_width, dy = fabs(p.y - center.y) - half_height;
  const vfloat ox = fmax(dx, 0.0f), oy = fmax(dy, 0.0f);
  return vsqrt(ox * ox + oy * oy) + fmin(fmax(dx, dy), 0.0f);
}

/* Exact: the rectangle shrunk by radius, then grown by it (radius <= the smaller half size). */
SDF_INLINE vfloat sd_rounded_rectangle(vec3v p, float4 center, float half_width, float half_height, float radius) {
  return sd_rectangle(p, center, half_width - radius, half_height - radius) - radius;
}

/* Exact: the distance to the segment a-b less radius. */
SDF_INLINE vfloat sd_segment(vec3v p, float4 a, float4 b, float radius) {
  const vfloat pax = p.x - a.x, pay = p.y - a.y;
  const float bax = b.x - a.x, bay = b.y - a.y;
  const vfloat h = clamp((pax * bax + pay * bay) / (bax * bax + bay * bay), 0.0f, 1.0f);
  const vfloat dx = pax - bax * h, dy = pay - bay * h;
  return vsqrt(dx * dx + dy * dy) - radius;
}

/* Exact (Quilez's regular polygon): the point turned into the sector of the edge between the
 * corners at angles 0 and 2 pi / sides (mirrored about the sector's bisector), then its distance
 * to that edge, negative on the centre's side. */
SDF_INLINE vfloat sd_regular_polygon(vec3v p, float4 center, float radius, int sides) {
  const float sector = 2.0f * M_PI_F / (float)sides;
  const vfloat x = p.x - center.x, y = p.y - center.y;
  const vfloat r = vsqrt(x * x + y * y);
  /* The angle from the sector's bisector, folded to [0, sector / 2]. */
  const vfloat angle = atan2(y, x);
  const vfloat from_bisector = fabs(angle - sector * (floor(angle / sector) + 0.5f));
  const vfloat qx = r * vcos(from_bisector), qy = r * vsin(from_bisector);
  /* The edge is x = apothem for |y| <= half its length, in this frame. */
  const float apothem = radius * cos(0.5f * sector), half_edge = radius * sin(0.5f * sector);
  const vfloat ex = qx - apothem, ey = qy - fmin(qy, half_edge);
  return select((vfloat)(1.0f), (vfloat)(-1.0f), MASK(ex < 0.0f)) * vsqrt(ex * ex + ey * ey);
}
