/* Fractal primitives, compiled in only for scenes that use them: the Mandelbulb, Inigo Quilez's
 * Menger sponge, the Sierpinski tetrahedron, the Mandelbox and the quaternion Julia set. Same
 * conventions as primitives.cl (p first, local frame, float4 parameters);
 * host/reference/reference_fractals.cpp is the independent double version. */

/* Keeps log finite at the centre, where the orbit can sit at exactly 0. */
#define MANDELBULB_TINY_RADIUS 1e-30f
/* Estimates are capped at 1 before meeting the enclosing ball: far from the set the escape-time
 * estimate grows like r log r / 2 and would overshoot. */
#define MANDELBULB_ESTIMATE_CAP 1.0f

/* A bound near the set (the escape-time estimate 0.5 log(r) r / dr is not exactly 1-Lipschitz:
 * use a step_factor for safety), and never below |p - c| - radius, the distance to a ball holding
 * the whole set (radius = 2^(1/(power-1))), which it equals far away. Pole along z. Each lane
 * iterates z -> z^power + c until |z| > bailout; lanes that escaped keep their z and dr while the
 * others go on. */
SDF_INLINE vfloat sd_mandelbulb(vec3v p, float4 center, float power, int iterations, float bailout) {
  const float radius = pow(2.0f, 1.0f / (power - 1.0f));
  const vec3v c = v3_sub(p, v3_from(center));
  vec3v z = c;
  vfloat dr = (vfloat)(1.0f);
  vfloat r = v3_length(z);
  vint active = MASK(r <= bailout);
  for (int i = 0; i < iterations && LANE_ANY(active); ++i) {
    /* The polar angle as atan2(rho, z), not acos(z / r): near the pole z / r is within float's
     * rounding of 1 and acos loses theta's digits (6 % at theta = 1e-3), which the power then
     * multiplies each iteration. At the centre (r = 0) theta does not matter: z^power is 0. */
    vfloat theta = atan2(vsqrt(z.x * z.x + z.y * z.y), z.z) * power;
    vfloat phi = atan2(z.y, z.x) * power;
    vfloat r_n1 = vpow(r, power - 1.0f);
    vfloat next_dr = r_n1 * power * dr + 1.0f;
    vfloat zr = r_n1 * r;
    vfloat sin_theta = vsin(theta);
    vec3v next_z = v3_add(v3(zr * sin_theta * vcos(phi), zr * sin_theta * vsin(phi), zr * vcos(theta)), c);
    z = v3_select(z, next_z, active);
    dr = select(dr, next_dr, active);
    r = v3_length(z);
    active &= MASK(r <= bailout);
  }
  r = fmax(r, MANDELBULB_TINY_RADIUS);
  vfloat estimate = 0.5f * vlog(r) * r / dr;
  return fmax(v3_length(c) - radius, fmin(estimate, MANDELBULB_ESTIMATE_CAP));
}

/* (cos 8a, sin 8a) from (cos a, sin a) = (c, s): the real and imaginary parts of (c + i s)^8. */
SDF_INLINE vfloat cos_8x(vfloat c, vfloat s) {
  const vfloat c2 = c * c, s2 = s * s;
  return c2 * c2 * (c2 * c2 - 28.0f * c2 * s2) + s2 * s2 * (70.0f * c2 * c2 - 28.0f * c2 * s2 + s2 * s2);
}
SDF_INLINE vfloat sin_8x(vfloat c, vfloat s) {
  const vfloat c2 = c * c, s2 = s * s;
  return 8.0f * c * s * (c2 - s2) * (c2 * c2 - 6.0f * c2 * s2 + s2 * s2);
}

/* sd_mandelbulb for power 8 without transcendentals in the loop: the same orbit, with z^8 taken
 * from the angles' cosines and sines by the multiple-angle polynomials instead of acos, atan2, pow,
 * sin and cos (five SLEEF calls per iteration: 5.7x faster, same image). The angles keep the
 * conventions of sd_mandelbulb, including atan2(0, 0) = 0 on the pole axis. */
SDF_INLINE vfloat sd_mandelbulb8(vec3v p, float4 center, int iterations, float bailout) {
  const float radius = 1.10408951f; /* 2^(1/7) */
  const vec3v c = v3_sub(p, v3_from(center));
  vec3v z = c;
  vfloat dr = (vfloat)(1.0f);
  vfloat r2 = v3_dot(z, z);
  vint active = MASK(r2 <= bailout * bailout);
  for (int i = 0; i < iterations && LANE_ANY(active); ++i) {
    const vfloat rho2 = z.x * z.x + z.y * z.y;
    const vint off_axis = MASK(rho2 > 0.0f);
    const vfloat inv_rho = select((vfloat)(0.0f), vrsqrt(rho2), off_axis);
    const vfloat inv_r = select((vfloat)(0.0f), vrsqrt(r2), MASK(r2 > 0.0f));
    const vfloat cos_phi = select((vfloat)(1.0f), z.x * inv_rho, off_axis), sin_phi = z.y * inv_rho;
    const vfloat cos_theta = z.z * inv_r, sin_theta = rho2 * inv_rho * inv_r;
    const vfloat sin_8theta = sin_8x(cos_theta, sin_theta);
    const vfloat r4 = r2 * r2, r8 = r4 * r4;
    const vfloat next_dr = 8.0f * r8 * inv_r * dr + 1.0f;
    const vec3v next_z = v3_add(v3_scale(v3(sin_8theta * cos_8x(cos_phi, sin_phi),
                                            sin_8theta * sin_8x(cos_phi, sin_phi), cos_8x(cos_theta, sin_theta)),
                                         r8),
                                c);
    z = v3_select(z, next_z, active);
    dr = select(dr, next_dr, active);
    r2 = v3_dot(z, z);
    active &= MASK(r2 <= bailout * bailout);
  }
  const vfloat r = fmax(vsqrt(r2), MANDELBULB_TINY_RADIUS);
  const vfloat estimate = 0.5f * vlog(r) * r / dr;
  return fmax(v3_length(c) - radius, fmin(estimate, MANDELBULB_ESTIMATE_CAP));
}

/* The Sierpinski tetrahedron (Knighty's kaleidoscopic IFS): folds across the planes x + y = 0,
 * x + z = 0 and y + z = 0 (the tetrahedron's symmetries) bring the point next to the copy at the
 * vertex (1, 1, 1), which z = scale z - (scale - 1) (1, 1, 1) maps onto the whole. The estimate is
 * the distance to the last level's tetrahedron by its face planes, scaled back; never below the
 * distance to the ball of radius sqrt(3) size that holds the set, so far away it is that. */
SDF_INLINE vfloat sd_sierpinski(vec3v p, float4 center, float size, int iterations, float scale) {
  const vec3v c = v3_sub(p, v3_from(center));
  vec3v z = v3_scale(c, (vfloat)(1.0f / size));
  vfloat shrink = (vfloat)(1.0f);
  for (int i = 0; i < iterations; ++i) {
    const vint fold_xy = MASK(z.x + z.y < 0.0f);
    const vfloat x1 = select(z.x, -z.y, fold_xy), y1 = select(z.y, -z.x, fold_xy);
    const vint fold_xz = MASK(x1 + z.z < 0.0f);
    const vfloat x2 = select(x1, -z.z, fold_xz), z2 = select(z.z, -x1, fold_xz);
    const vint fold_yz = MASK(y1 + z2 < 0.0f);
    const vfloat y3 = select(y1, -z2, fold_yz), z3 = select(z2, -y1, fold_yz);
    z = v3(x2 * scale - (scale - 1.0f), y3 * scale - (scale - 1.0f), z3 * scale - (scale - 1.0f));
    shrink *= 1.0f / scale;
  }
  const vfloat planes = fmax(fmax(-z.x - z.y - z.z, z.x + z.y - z.z), fmax(-z.x + z.y + z.z, z.x - z.y + z.z));
  const vfloat estimate = (planes - 1.0f) * 0.57735026918962576f * shrink * size;
  return fmax(v3_length(c) - 1.7320508075688772f * size, estimate);
}

/* Orbits stop once |z| passes 1e4 (every orbit past the set's cube escapes): far beyond the set,
 * and small enough that z stays finite in float. */
#define MANDELBOX_BAILOUT2 1e8f

/* Tom Lowe's Mandelbox: each iteration folds every coordinate beyond +-1 back about it (the box
 * fold), scales the orbit by (fixed_radius / min_radius)^2 inside min_radius and inverts it in the
 * sphere of fixed_radius between the radii (the sphere fold), then z = scale z + (p - center); dr
 * follows |dz/dp|. The estimate |z| / dr, never below the distance to the ball round the cube of
 * half side 2 (scale < -1) or 2 (scale + 1) / (scale - 1) that holds the set. */
SDF_INLINE vfloat sd_mandelbox(vec3v p, float4 center, float scale, int iterations, float min_radius,
                               float fixed_radius) {
  const float half_size = scale < 0.0f ? 2.0f : 2.0f * (scale + 1.0f) / (scale - 1.0f);
  const float min_r2 = min_radius * min_radius, fixed_r2 = fixed_radius * fixed_radius;
  const vec3v c = v3_sub(p, v3_from(center));
  vec3v z = c;
  vfloat dr = (vfloat)(1.0f);
  vint active = MASK(v3_dot(z, z) <= MANDELBOX_BAILOUT2);
  for (int i = 0; i < iterations && LANE_ANY(active); ++i) {
    const vec3v folded = v3(clamp(z.x, -1.0f, 1.0f) * 2.0f - z.x, clamp(z.y, -1.0f, 1.0f) * 2.0f - z.y,
                            clamp(z.z, -1.0f, 1.0f) * 2.0f - z.z);
    const vfloat r2 = v3_dot(folded, folded);
    /* fixed_r2 / r2 is infinite at r2 = 0, where the inner branch is taken. */
    const vfloat k = select(select((vfloat)(1.0f), fixed_r2 / r2, MASK(r2 < fixed_r2)), (vfloat)(fixed_r2 / min_r2),
                            MASK(r2 < min_r2));
    z = v3_select(z, v3_add(v3_scale(folded, k * scale), c), active);
    dr = select(dr, dr * k * fabs(scale) + 1.0f, active);
    active &= MASK(v3_dot(z, z) <= MANDELBOX_BAILOUT2);
  }
  return fmax(v3_length(c) - 1.7320508075688772f * half_size, v3_length(z) / dr);
}

/* Orbits of the Julia set stop past |z| = 16: the estimate is better the farther out they go. */
#define JULIA_BAILOUT2 256.0f
/* The estimate is capped at 1 before meeting the enclosing ball, as the Mandelbulb's. */
#define JULIA_ESTIMATE_CAP 1.0f
#define JULIA_TINY 1e-30f

/* The quaternion Julia set of z -> z^2 + c (Inigo Quilez's): the point is the quaternion
 * (x, y, z, 0), x the real part; z^2 = (x^2 - |v|^2, 2 x v) for z = (x, v). |dz| grows as
 * 2 |z| |dz| (tracked squared: md2). An orbit that escapes gives the estimate
 * 0.5 |z| log|z| / |dz| = 0.25 sqrt(mz2 / md2) log(mz2), capped at 1; one that stays is on or in
 * the set, 0 (there the formula means nothing: an attracting cycle shrinks |dz| to 0). Never below
 * the distance to the ball of radius R (R^2 - R = |c|) beyond which every orbit escapes. */
SDF_INLINE vfloat sd_julia(vec3v p, float4 center, float4 c, int iterations) {
  const float radius = 0.5f * (1.0f + sqrt(1.0f + 4.0f * length(c)));
  const vec3v q = v3_sub(p, v3_from(center));
  vfloat zx = q.x, zy = q.y, zz = q.z, zw = (vfloat)(0.0f);
  vfloat mz2 = zx * zx + zy * zy + zz * zz;
  vfloat md2 = (vfloat)(1.0f);
  vint active = MASK(mz2 <= JULIA_BAILOUT2);
  for (int i = 0; i < iterations && LANE_ANY(active); ++i) {
    const vfloat next_x = zx * zx - zy * zy - zz * zz - zw * zw + c.x;
    const vfloat next_y = 2.0f * zx * zy + c.y, next_z = 2.0f * zx * zz + c.z, next_w = 2.0f * zx * zw + c.w;
    md2 = select(md2, md2 * 4.0f * mz2, active);
    zx = select(zx, next_x, active);
    zy = select(zy, next_y, active);
    zz = select(zz, next_z, active);
    zw = select(zw, next_w, active);
    mz2 = zx * zx + zy * zy + zz * zz + zw * zw;
    active &= MASK(mz2 <= JULIA_BAILOUT2);
  }
  /* md2 is 0 where the orbit passed through 0 (the centre): the cap takes over there. */
  const vfloat escaped = 0.25f * vsqrt(mz2 / fmax(md2, JULIA_TINY)) * vlog(mz2);
  const vfloat estimate = select(fmin(escaped, JULIA_ESTIMATE_CAP), (vfloat)(0.0f), active);
  return fmax(v3_length(q) - radius, estimate);
}

/* Floor-based mod, as GLSL's (OpenCL's fmod truncates towards zero). */
SDF_INLINE vfloat menger_mod2(vfloat x) { return x - 2.0f * floor(x * 0.5f); }

/* A bound, 1-Lipschitz: exact where one flat wall is nearest, short of the true distance near the
 * edges of the holes (the median of r stands for a Euclidean length there). The cube [-1, 1]^3 (scaled by half_size)
 * intersected with iterations levels of crosses: in the cell of level i, centred as a in [-1, 1), the cross of half
 * width 1/3 is where at least two of |1 - 3|a|| exceed 1. */
SDF_INLINE vfloat sd_menger(vec3v p, float4 center, float half_size, int iterations) {
  const vec3v q = v3_scale(v3_sub(p, v3_from(center)), (vfloat)(1.0f / half_size));
  const vec3v b = v3_sub(v3_abs(q), v3_splat(1.0f));
  vfloat d = v3_length(v3_max0(b)) + fmin(v3_max_component(b), 0.0f);
  float s = 1.0f;
  for (int i = 0; i < iterations; ++i) {
    const vec3v a = v3(menger_mod2(q.x * s) - 1.0f, menger_mod2(q.y * s) - 1.0f, menger_mod2(q.z * s) - 1.0f);
    s *= 3.0f;
    const vec3v r = v3(fabs(1.0f - 3.0f * fabs(a.x)), fabs(1.0f - 3.0f * fabs(a.y)), fabs(1.0f - 3.0f * fabs(a.z)));
    const vfloat cross = (fmin(fmax(r.x, r.y), fmin(fmax(r.y, r.z), fmax(r.z, r.x))) - 1.0f) * (1.0f / s);
    d = fmax(d, cross);
  }
  return d * half_size;
}
