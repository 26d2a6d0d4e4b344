/* Evaluates the scene's distance function, material and primitive number at batches of points (LANES per
 * work-item): for tests against closed forms, clmarch.field and the samples of clmarch mesh. Inputs and
 * outputs are planes padded to whole packets: the points and the two distances of `real` (doubles in a
 * double program, so that `clmarch field --precision double` neither rounds its points nor its
 * answers to float), colours and numbers of float. Each point is origin + (x, y, z): origin comes
 * as a float pair hi + lo, which a double program adds in double, so that the points near a far origin
 * keep the precision of their offsets. */

__kernel void eval_points(__global const real* xs, __global const real* ys, __global const real* zs,
                          __global real* distance, __global real* color_distance, __global float* red,
                          __global float* green, __global float* blue, __global float* ids, SceneValues values,
                          const float4 origin_hi, const float4 origin_lo) {
  const int base = (int)get_global_id(0) * LANES;
  const real ox = (real)origin_hi.x + (real)origin_lo.x;
  const real oy = (real)origin_hi.y + (real)origin_lo.y;
  const real oz = (real)origin_hi.z + (real)origin_lo.z;
  const vec3v p = v3(LOAD_LANES(base, xs) + ox, LOAD_LANES(base, ys) + oy, LOAD_LANES(base, zs) + oz);
  vec3v albedo, surface, emission;
  vfloat id;
  STORE_REAL_LANES(map(values, p), base, distance);
  STORE_REAL_LANES(map_color(values, p, &albedo, &surface, &emission, &id), base, color_distance);
  STORE_LANES(id, base, ids);
  STORE_LANES(albedo.x, base, red);
  STORE_LANES(albedo.y, base, green);
  STORE_LANES(albedo.z, base, blue);
}

/* clmarch mesh (host/mesh/device_field.cpp): the samples of whole bricks of grid points, generated
 * here rather than sent. Brick b's corner (in cells) is bricks[b].xyz; its side samples
 * brick_samples points, x fastest, then y, then z, and its values start at b * stride (stride >=
 * brick_samples^3, a whole number of packets, so that a packet never spans two bricks; the points
 * past the brick's last are evaluated and ignored). Point (i, j, k) of the grid is origin +
 * (i, j, k) * cell. */
__kernel void mesh_sample_bricks(__global const int4* bricks, __global float* distance, SceneValues values,
                                 const int brick_samples, const int stride, const float cell, const float4 origin_hi,
                                 const float4 origin_lo) {
  const int base = (int)get_global_id(0) * LANES;
  const int4 corner = bricks[base / stride];
  const vint at = (vint)(base % stride) + LANE_IOTA;
  const vint x = at % brick_samples;
  const vint y = (at / brick_samples) % brick_samples;
  const vint z = at / (brick_samples * brick_samples);
  const real ox = (real)origin_hi.x + (real)origin_lo.x;
  const real oy = (real)origin_hi.y + (real)origin_lo.y;
  const real oz = (real)origin_hi.z + (real)origin_lo.z;
  const vec3v p = v3(TO_VFLOAT(x + corner.x) * (real)cell + ox, TO_VFLOAT(y + corner.y) * (real)cell + oy,
                     TO_VFLOAT(z + corner.z) * (real)cell + oz);
  STORE_LANES(map(values, p), base, distance);
}

/* clmarch mesh: each vertex moved along its grid edge onto the level, then its normal and colour.
 * The edge runs from offset (ax, ay, az) to that plus (dx, dy, dz), where the field is f0 and f1
 * (on opposite sides of level). The place t along it is found by false position with Anderson and
 * Bjorck's rule (when the same end is replaced twice in a row, the other end's value is scaled by
 * 1 - f(new) / f(replaced), or halved), and bisection once one end was kept three times: a kinked
 * field (inside a box's corner) holds plain false position to a crawl. A lane stops once the field
 * is within tolerance of level or after max_steps evaluations. The normal is the field's gradient
 * by differences normal_step from the vertex, or where it vanishes the edge's direction up the field;
 * the colour is map_color's albedo at the vertex. host/mesh/reference_field.cpp does the same in
 * double on the CPU. */
__kernel void mesh_place_vertices(__global const float* ax, __global const float* ay, __global const float* az,
                                  __global const float* dx, __global const float* dy, __global const float* dz,
                                  __global const float* f0, __global const float* f1, __global float* place,
                                  __global float* nx, __global float* ny, __global float* nz, __global float* red,
                                  __global float* green, __global float* blue, __global float* evaluations,
                                  SceneValues values, const float level, const float tolerance, const int max_steps,
                                  const float normal_step, const float4 origin_hi, const float4 origin_lo) {
  const int base = (int)get_global_id(0) * LANES;
  const vec3v origin =
      v3((vfloat)((real)origin_hi.x + (real)origin_lo.x), (vfloat)((real)origin_hi.y + (real)origin_lo.y),
         (vfloat)((real)origin_hi.z + (real)origin_lo.z));
  const vec3v a = v3_add(origin, v3(LOAD_LANES(base, ax), LOAD_LANES(base, ay), LOAD_LANES(base, az)));
  const vec3v d = v3(LOAD_LANES(base, dx), LOAD_LANES(base, dy), LOAD_LANES(base, dz));
  const vfloat lv = (vfloat)((real)level);
  vfloat fa = LOAD_LANES(base, f0) - lv;
  vfloat fb = LOAD_LANES(base, f1) - lv;
  const vfloat up = select((vfloat)(-1.0f), (vfloat)(1.0f), MASK(fb > fa));
  vfloat ta = (vfloat)(0.0f), tb = (vfloat)(1.0f);
  /* The linear interpolation first; halfway where it is no number (equal or non-finite ends). */
  vfloat t = -fa / (fb - fa);
  t = select((vfloat)(0.5f), clamp(t, (vfloat)(0.0f), (vfloat)(1.0f)), MASK(isfinite(t)));
  /* Which end the last step replaced (1 a, 2 b, 0 none) and how many steps in a row kept the other. */
  vint last = (vint)(0), kept = (vint)(0);
  vint active = MASK(fa * fb < 0.0f);
  vfloat steps = (vfloat)(0.0f);
  for (int step = 0; step < max_steps && LANE_ANY(active); ++step) {
    const vfloat f = map(values, v3_add(a, v3_scale(d, t))) - lv;
    steps += select((vfloat)(0.0f), (vfloat)(1.0f), active);
    active &= MASK(fabs(f) > (real)tolerance) & MASK(isfinite(f));
    const vint replace_a = MASK((f < 0.0f) == (fa < 0.0f));
    const vint replaced = select((vint)(2), (vint)(1), replace_a);
    kept = select((vint)(0), kept + 1, MASK(replaced == last));
    const vfloat old = select(fb, fa, replace_a);
    const vfloat ratio = f / old;
    const vfloat scale = select((vfloat)(0.5f), 1.0f - ratio, MASK(ratio < 1.0f));
    const vint scaled = MASK(kept > 0);
    const vfloat new_fa = select(select(fa, fa * scale, scaled), f, replace_a);
    const vfloat new_fb = select(f, select(fb, fb * scale, scaled), replace_a);
    const vfloat new_ta = select(ta, t, replace_a);
    const vfloat new_tb = select(t, tb, replace_a);
    const vfloat new_span = new_fb - new_fa;
    vfloat next = select((vfloat)(0.5f) * (new_ta + new_tb), new_ta - new_fa * (new_tb - new_ta) / new_span,
                         MASK(new_span != 0.0f));
    next = select(next, (vfloat)(0.5f) * (new_ta + new_tb), MASK(kept >= 2));
    fa = select(fa, new_fa, active);
    fb = select(fb, new_fb, active);
    ta = select(ta, new_ta, active);
    tb = select(tb, new_tb, active);
    last = select(last, replaced, active);
    t = select(t, clamp(next, (vfloat)(0.0f), (vfloat)(1.0f)), active);
  }
  const vec3v p = v3_add(a, v3_scale(d, t));
  /* The gradient from four taps at the corners of a tetrahedron (p + h k, k = (1,-1,-1), (-1,-1,1),
   * (-1,1,-1), (1,1,1)): second order like central differences, with four evaluations for six. */
  const real h = (real)normal_step;
  const vfloat t1 = map(values, v3(p.x + h, p.y - h, p.z - h));
  const vfloat t2 = map(values, v3(p.x - h, p.y - h, p.z + h));
  const vfloat t3 = map(values, v3(p.x - h, p.y + h, p.z - h));
  const vfloat t4 = map(values, v3(p.x + h, p.y + h, p.z + h));
  const vec3v gradient = v3(t1 - t2 - t3 + t4, -t1 - t2 + t3 + t4, -t1 + t2 - t3 + t4);
  const vfloat length2 = v3_dot(gradient, gradient);
  const vec3v normal =
      v3_select(v3_normalize(v3_scale(d, up)), v3_normalize(gradient), MASK(length2 > 0.0f) & MASK(isfinite(length2)));
  vec3v albedo, surface, emission;
  vfloat id;
  map_color(values, p, &albedo, &surface, &emission, &id);
  STORE_LANES(t, base, place);
  STORE_LANES(normal.x, base, nx);
  STORE_LANES(normal.y, base, ny);
  STORE_LANES(normal.z, base, nz);
  STORE_LANES(albedo.x, base, red);
  STORE_LANES(albedo.y, base, green);
  STORE_LANES(albedo.z, base, blue);
  STORE_LANES(steps + 5.0f, base, evaluations);
}
