/* The blend operators (host/scene/node_kinds.def's CLMARCH_BLEND lines), each written from its
 * formula in the plane of the operands' distances: a the accumulated left operand, b the next
 * child, r the radius. The chamfer, round, columns, pipe and engrave families are exact distances
 * in that plane, so up to sqrt 2 steeper in space where the operands' gradients are not orthogonal
 * (estimates: host/scene/scene.cpp's operator_lipschitz); the stairs, xor, groove and tongue are
 * 1-Lipschitz (bounds). The *_edge, *_cut and *_part functions are the blended term alone, which
 * the color rules compare with a (host/codegen/blend_code.cpp). */

#ifdef DOUBLE_PRECISION
#define BLEND_SQRT_HALF 0.70710678118654752440
#define BLEND_SQRT_TWO 1.41421356237309504880
#else
#define BLEND_SQRT_HALF 0.70710678f
#define BLEND_SQRT_TWO 1.41421356f
#endif

/* The 45-degree bevel: the line a + b = r across the corner. */
SDF_INLINE vfloat op_union_chamfer(vfloat a, vfloat b, float r) {
  return fmin(fmin(a, b), (a + b - r) * BLEND_SQRT_HALF);
}
SDF_INLINE vfloat op_intersection_chamfer(vfloat a, vfloat b, float r) {
  return fmax(fmax(a, b), (a + b + r) * BLEND_SQRT_HALF);
}
/* a minus b. */
SDF_INLINE vfloat op_difference_chamfer(vfloat a, vfloat b, float r) { return op_intersection_chamfer(a, -b, r); }

/* The quarter circle of radius r centred at (r, r), tangent to both operands. */
SDF_INLINE vfloat op_union_round(vfloat a, vfloat b, float r) {
  const vfloat u = fmax(r - a, 0.0f);
  const vfloat v = fmax(r - b, 0.0f);
  return fmax(fmin(a, b), r) - vsqrt(u * u + v * v);
}
/* The quarter circle centred at (-r, -r). */
SDF_INLINE vfloat op_intersection_round(vfloat a, vfloat b, float r) {
  const vfloat u = fmax(a + r, 0.0f);
  const vfloat v = fmax(b + r, 0.0f);
  return fmin(fmax(a, b), -r) + vsqrt(u * u + v * v);
}
SDF_INLINE vfloat op_difference_round(vfloat a, vfloat b, float r) { return op_intersection_round(a, -b, r); }

/* The steps' field: the quadrants {a < corner.a, b < corner.b} whose corners are the points
 * ((j + 1/2) s, r - (j + 1/2) s), s = r / steps, on the line a + b = r, as
 * max(a - corner.a, b - corner.b) of the nearest corner: with t = b - a - r + s, whose multiples
 * of 2 s are the corners, that is (a + b - r + |t - 2 s round(t / 2 s)|) / 2. Corners beyond the
 * ends (j < 0, j >= steps) lie inside a or b's half plane, so the min with a and b hides them. */
SDF_INLINE vfloat union_stairs_edge(vfloat a, vfloat b, float r, float steps) {
  const real s = (real)r / (real)steps;
  const vfloat t = b - a - r + s;
  return 0.5f * (a + b - r + fabs(t - 2.0f * s * round(t / (2.0f * s))));
}
SDF_INLINE vfloat op_union_stairs(vfloat a, vfloat b, float r, float steps) {
  return fmin(fmin(a, b), union_stairs_edge(a, b, r, steps));
}
SDF_INLINE vfloat op_intersection_stairs(vfloat a, vfloat b, float r, float steps) {
  return -op_union_stairs(-a, -b, r, steps);
}
SDF_INLINE vfloat op_difference_stairs(vfloat a, vfloat b, float r, float steps) {
  return op_intersection_stairs(a, -b, r, steps);
}

/* The columns' field: in the frame turned 45 degrees, x = (a + b) / sqrt 2 and y = (b - a) /
 * sqrt 2, steps disks of radius c = r / (sqrt 2 (steps + sqrt 2)) centred on the line
 * x = x0 = r / sqrt 2 - c at y = (2 k - steps + 1) c, k = 0 .. steps - 1: they touch each other,
 * the line a + b = r, and the outer ones a = 0 and b = 0; the half plane x < x0 fills behind them. */
SDF_INLINE vfloat union_columns_edge(vfloat a, vfloat b, float r, float steps) {
  const real c = (real)r * BLEND_SQRT_HALF / ((real)steps + BLEND_SQRT_TWO);
  const vfloat x = (a + b) * BLEND_SQRT_HALF - ((real)r * BLEND_SQRT_HALF - c);
  const vfloat y = (b - a) * BLEND_SQRT_HALF;
  const real last = (real)steps - 1.0f;
  const vfloat k = clamp(round(y / (2.0f * c) + 0.5f * last), (real)0.0f, last);
  const vfloat dy = y - (2.0f * k - last) * c;
  return fmin(x, vsqrt(x * x + dy * dy) - c);
}
SDF_INLINE vfloat op_union_columns(vfloat a, vfloat b, float r, float steps) {
  return fmin(fmin(a, b), union_columns_edge(a, b, r, steps));
}
SDF_INLINE vfloat op_intersection_columns(vfloat a, vfloat b, float r, float steps) {
  return -op_union_columns(-a, -b, r, steps);
}
SDF_INLINE vfloat op_difference_columns(vfloat a, vfloat b, float r, float steps) {
  return op_intersection_columns(a, -b, r, steps);
}

/* Inside exactly one operand. */
SDF_INLINE vfloat op_xor(vfloat a, vfloat b) { return fmax(fmin(a, b), -fmax(a, b)); }

/* A tube of radius r along the curve where a = b = 0. */
SDF_INLINE vfloat op_pipe(vfloat a, vfloat b, float r) { return vsqrt(a * a + b * b) - r; }

/* The V-shaped groove cut into a along b's surface: depth r, half width r at a's surface. */
SDF_INLINE vfloat engrave_cut(vfloat a, vfloat b, float r) { return (a + r - fabs(b)) * BLEND_SQRT_HALF; }
SDF_INLINE vfloat op_engrave(vfloat a, vfloat b, float r) { return fmax(a, engrave_cut(a, b, r)); }

/* The square groove cut into a along b's surface: depth ra, half width rb. */
SDF_INLINE vfloat groove_cut(vfloat a, vfloat b, float ra, float rb) { return fmin(a + ra, rb - fabs(b)); }
SDF_INLINE vfloat op_groove(vfloat a, vfloat b, float ra, float rb) { return fmax(a, groove_cut(a, b, ra, rb)); }

/* The square tongue raised on a along b's surface: height ra, half width rb. */
SDF_INLINE vfloat tongue_part(vfloat a, vfloat b, float ra, float rb) { return fmax(a - ra, fabs(b) - rb); }
SDF_INLINE vfloat op_tongue(vfloat a, vfloat b, float ra, float rb) { return fmin(a, tongue_part(a, b, ra, rb)); }
