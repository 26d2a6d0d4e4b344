/* Distance functions of the primitives (Inigo Quilez's list), one per node kind of
 * host/scene/node_kinds.def. Each takes the sample point first, in the node's local frame, and
 * says whether it returns the exact distance or a bound. Vector parameters arrive as float4
 * literals (xyz used). */

/* Exact. */
SDF_INLINE vfloat sd_sphere(vec3v p, float4 center, float radius) {
  return v3_length(v3_sub(p, v3_from(center))) - radius;
}

/* Exact. */
SDF_INLINE vfloat sd_box(vec3v p, float4 center, float4 half_size) {
  vec3v q = v3_sub(v3_abs(v3_sub(p, v3_from(center))), v3_from(half_size));
  return v3_length(v3_max0(q)) + fmin(v3_max_component(q), 0.0f);
}

/* Exact; half_size includes the rounding radius. */
SDF_INLINE vfloat sd_round_box(vec3v p, float4 center, float4 half_size, float radius) {
  vec3v q = v3_sub(v3_abs(v3_sub(p, v3_from(center))), v3_from(half_size - radius));
  return v3_length(v3_max0(q)) + fmin(v3_max_component(q), 0.0f) - radius;
}

/* Exact. The three terms are the bars along x, y and z. */
SDF_INLINE vfloat sd_box_frame(vec3v p, float4 center, float4 half_size, float thickness) {
  vec3v a = v3_sub(v3_abs(v3_sub(p, v3_from(center))), v3_from(half_size));
  vec3v q = v3_sub(v3_abs(v3_add(a, v3_splat(thickness))), v3_splat(thickness));
  vec3v bar_x = v3(a.x, q.y, q.z);
  vec3v bar_y = v3(q.x, a.y, q.z);
  vec3v bar_z = v3(q.x, q.y, a.z);
  vfloat dx = v3_length(v3_max0(bar_x)) + fmin(v3_max_component(bar_x), 0.0f);
  vfloat dy = v3_length(v3_max0(bar_y)) + fmin(v3_max_component(bar_y), 0.0f);
  vfloat dz = v3_length(v3_max0(bar_z)) + fmin(v3_max_component(bar_z), 0.0f);
  return fmin(fmin(dx, dy), dz);
}

/* Exact. Torus in the xz plane. */
SDF_INLINE vfloat sd_torus(vec3v p, float4 center, float major_radius, float minor_radius) {
  vec3v q = v3_sub(p, v3_from(center));
  vfloat ring = vsqrt(q.x * q.x + q.z * q.z) - major_radius;
  return vsqrt(ring * ring + q.y * q.y) - minor_radius;
}

/* Exact. normal is unit length (the loader normalises it). */
SDF_INLINE vfloat sd_plane(vec3v p, float4 normal, float offset) {
  return p.x * normal.x + p.y * normal.y + p.z * normal.z + offset;
}

/* Exact. Segment a-b thickened by radius. */
SDF_INLINE vfloat sd_capsule(vec3v p, float4 a, float4 b, float radius) {
  vec3v pa = v3_sub(p, v3_from(a));
  float4 ba = b - a;
  vfloat h = clamp((pa.x * ba.x + pa.y * ba.y + pa.z * ba.z) / dot(ba.xyz, ba.xyz), 0.0f, 1.0f);
  return v3_length(v3_sub(pa, v3_scale(v3_from(ba), h))) - radius;
}

/* Exact. Capped cylinder along y. */
SDF_INLINE vfloat sd_cylinder(vec3v p, float4 center, float radius, float half_height) {
  vec3v q = v3_sub(p, v3_from(center));
  vfloat dr = vsqrt(q.x * q.x + q.z * q.z) - radius;
  vfloat dh = fabs(q.y) - half_height;
  vfloat outside_r = fmax(dr, 0.0f);
  vfloat outside_h = fmax(dh, 0.0f);
  return fmin(fmax(dr, dh), 0.0f) + vsqrt(outside_r * outside_r + outside_h * outside_h);
}

/* Exact. Infinite cylinder along y, its axis through center. */
SDF_INLINE vfloat sd_infinite_cylinder(vec3v p, float4 center, float radius) {
  vfloat dx = p.x - center.x;
  vfloat dz = p.z - center.z;
  return vsqrt(dx * dx + dz * dz) - radius;
}

/* Exact (Inigo Quilez): the solid |x| + |y| + |z| <= size. Where 3 q.x < m for the first
 * coordinate of the folded point that allows it, the nearest point is on an edge region of the
 * face, found in that coordinate's frame q; elsewhere it is the face plane, at m / sqrt(3). */
SDF_INLINE vfloat sd_octahedron(vec3v p, float4 center, float size) {
  vec3v a = v3_abs(v3_sub(p, v3_from(center)));
  vfloat m = a.x + a.y + a.z - size;
  vint use_x = MASK(3.0f * a.x < m);
  vint use_y = MASK(3.0f * a.y < m) & ~use_x;
  vint use_any = use_x | use_y | MASK(3.0f * a.z < m);
  /* q = a.xyz, a.yzx or a.zxy. */
  vfloat qx = select(select(a.z, a.y, use_y), a.x, use_x);
  vfloat qy = select(select(a.x, a.z, use_y), a.y, use_x);
  vfloat qz = select(select(a.y, a.x, use_y), a.z, use_x);
  vfloat k = clamp(0.5f * (qz - qy + size), 0.0f, size);
  vfloat dy = qy - size + k;
  vfloat dz = qz - k;
  vfloat edge = vsqrt(qx * qx + dy * dy + dz * dz);
  return select(m * 0.57735027f, edge, use_any);
}

/* Exact (Inigo Quilez's hexagonal prism, its axis turned to y): radius is the distance from the
 * axis to each flat side, one of which faces +z. */
SDF_INLINE vfloat sd_hex_prism(vec3v p, float4 center, float radius, float half_height) {
  vec3v a = v3_abs(v3_sub(p, v3_from(center)));
  /* Fold the xz quarter across the side at 60 degrees: k = (-cos 30, sin 30). */
  vfloat fold = 2.0f * fmin(-0.8660254f * a.x + 0.5f * a.z, 0.0f);
  vfloat x = a.x + 0.8660254f * fold;
  vfloat z = a.z - 0.5f * fold;
  vfloat edge = 0.57735027f * radius;
  vfloat cx = x - clamp(x, -edge, edge);
  vfloat cz = z - radius;
  vfloat side = vsqrt(cx * cx + cz * cz) * sign(cz);
  vfloat cap = a.y - half_height;
  vfloat outside_side = fmax(side, 0.0f);
  vfloat outside_cap = fmax(cap, 0.0f);
  return fmin(fmax(side, cap), 0.0f) + vsqrt(outside_side * outside_side + outside_cap * outside_cap);
}

/* Exact (Inigo Quilez's capped cone): radius bottom_radius at y = -half_height, top_radius at
 * +half_height. In the half plane (r, y): ca is the offset to the nearer cap disc, cb to the
 * slanted side segment; inside is where both say so. */
SDF_INLINE vfloat sd_capped_cone(vec3v p, float4 center, float half_height, float bottom_radius, float top_radius) {
  vec3v l = v3_sub(p, v3_from(center));
  vfloat r = vsqrt(l.x * l.x + l.z * l.z);
  vfloat y = l.y;
  vfloat cap_radius = select((vfloat)(top_radius), (vfloat)(bottom_radius), MASK(y < 0.0f));
  vfloat ca_x = r - fmin(r, cap_radius);
  vfloat ca_y = fabs(y) - half_height;
  float k2x = top_radius - bottom_radius;
  float k2y = 2.0f * half_height;
  vfloat t = clamp(((top_radius - r) * k2x + (half_height - y) * k2y) / (k2x * k2x + k2y * k2y), 0.0f, 1.0f);
  vfloat cb_x = r - top_radius + k2x * t;
  vfloat cb_y = y - half_height + k2y * t;
  vfloat s = select((vfloat)(1.0f), (vfloat)(-1.0f), MASK(cb_x < 0.0f) & MASK(ca_y < 0.0f));
  return s * vsqrt(fmin(ca_x * ca_x + ca_y * ca_y, cb_x * cb_x + cb_y * cb_y));
}

/* A bound (Inigo Quilez's ellipsoid, k0 (k0 - 1) / k1): exact on the surface and on the axes'
 * spheres, below the true distance elsewhere. At the centre (k1 = 0) it is -min(radii). */
SDF_INLINE vfloat sd_ellipsoid(vec3v p, float4 center, float4 radii) {
  vec3v l = v3_sub(p, v3_from(center));
  vec3v q0 = v3(l.x / radii.x, l.y / radii.y, l.z / radii.z);
  vec3v q1 = v3(q0.x / radii.x, q0.y / radii.y, q0.z / radii.z);
  vfloat k0 = v3_length(q0);
  vfloat k1 = v3_length(q1);
  vfloat inner = (vfloat)(-fmin(radii.x, fmin(radii.y, radii.z)));
  return select(inner, k0 * (k0 - 1.0f) / k1, MASK(k1 > 0.0f));
}

/* Exact (Inigo Quilez's sdCone): apex at center, the base disc height below, of radius
 * height tan(angle). In the half plane (r, y), q is the rim; a is the offset to the slanted
 * side, b to the base; s < 0 inside both. */
SDF_INLINE vfloat sd_cone(vec3v p, float4 center, float angle, float height) {
  vec3v l = v3_sub(p, v3_from(center));
  float qx = height * sinpi(angle / 180.0f) / cospi(angle / 180.0f);
  float qy = -height;
  vfloat wx = vsqrt(l.x * l.x + l.z * l.z);
  vfloat wy = l.y;
  vfloat ta = clamp((wx * qx + wy * qy) / (qx * qx + qy * qy), 0.0f, 1.0f);
  vfloat ax = wx - qx * ta;
  vfloat ay = wy - qy * ta;
  vfloat bx = wx - qx * clamp(wx / qx, 0.0f, 1.0f);
  vfloat by = wy - qy;
  vfloat s = fmax(wy * qx - wx * qy, qy - wy);
  return vsqrt(fmin(ax * ax + ay * ay, bx * bx + by * by)) * sign(s);
}

/* Exact (Inigo Quilez's sdRoundedCylinder, sized by the outer radius and half height): the
 * cylinder shrunk by edge_radius, grown back by it. */
SDF_INLINE vfloat sd_rounded_cylinder(vec3v p, float4 center, float radius, float half_height, float edge_radius) {
  vec3v l = v3_sub(p, v3_from(center));
  vfloat dr = vsqrt(l.x * l.x + l.z * l.z) - (radius - edge_radius);
  vfloat dh = fabs(l.y) - (half_height - edge_radius);
  vfloat outside_r = fmax(dr, 0.0f);
  vfloat outside_h = fmax(dh, 0.0f);
  return fmin(fmax(dr, dh), 0.0f) + vsqrt(outside_r * outside_r + outside_h * outside_h) - edge_radius;
}

/* Exact (Inigo Quilez's sdRoundCone between two points, one square root): y is the position
 * along a-b times |b - a|^2, x2 the squared distance from the axis times |b - a|^4; the
 * comparisons with k pick the sphere at b, the sphere at a or the tangent cone between them.
 * Needs |radius_a - radius_b| < |b - a| (the loader checks it). */
SDF_INLINE vfloat sd_round_cone(vec3v p, float4 a, float4 b, float radius_a, float radius_b) {
  float4 ba = b - a;
  float l2 = dot(ba.xyz, ba.xyz);
  float rr = radius_a - radius_b;
  float a2 = l2 - rr * rr;
  float il2 = 1.0f / l2;
  vec3v pa = v3_sub(p, v3_from(a));
  vfloat y = v3_dot(pa, v3_from(ba));
  vfloat z = y - l2;
  vec3v off = v3_sub(v3_scale(pa, (vfloat)(l2)), v3_scale(v3_from(ba), y));
  vfloat x2 = v3_dot(off, off);
  vfloat y2 = y * y * l2;
  vfloat z2 = z * z * l2;
  vfloat k = sign(rr) * rr * rr * x2;
  vfloat near_b = vsqrt(x2 + z2) * il2 - radius_b;
  vfloat near_a = vsqrt(x2 + y2) * il2 - radius_a;
  vfloat side = (vsqrt(x2 * a2 * il2) + y * rr) * il2 - radius_a;
  vfloat d = select(side, near_a, MASK(sign(y) * a2 * y2 < k));
  return select(d, near_b, MASK(sign(z) * a2 * z2 > k));
}

/* Exact (Inigo Quilez's sdCappedCylinder between two points): x is the distance from the axis
 * less radius, y the distance beyond the nearer cap, both times |b - a|^2 (one division at the end);
 * inside both it is the nearer, outside the length of their positive parts. */
SDF_INLINE vfloat sd_capped_cylinder(vec3v p, float4 a, float4 b, float radius) {
  float4 ba = b - a;
  float baba = dot(ba.xyz, ba.xyz);
  vec3v pa = v3_sub(p, v3_from(a));
  vfloat paba = v3_dot(pa, v3_from(ba));
  vfloat x = v3_length(v3_sub(v3_scale(pa, (vfloat)(baba)), v3_scale(v3_from(ba), paba))) - radius * baba;
  vfloat y = fabs(paba - 0.5f * baba) - 0.5f * baba;
  vfloat x2 = x * x;
  vfloat y2 = y * y * baba;
  vfloat outside = select((vfloat)(0.0f), x2, MASK(x > 0.0f)) + select((vfloat)(0.0f), y2, MASK(y > 0.0f));
  vfloat d = select(outside, -fmin(x2, y2), MASK(fmax(x, y) < 0.0f));
  return sign(d) * vsqrt(fabs(d)) / baba;
}

/* Exact (Inigo Quilez's sdCappedCone between two points): in the half plane of (x, the distance
 * from the axis; t, the position along a-b from 0 to 1), ca is the offset to the nearer cap disc
 * and cb to the slanted side segment, their lengths measured with t scaled back by |b - a|; inside
 * where both say so. */
SDF_INLINE vfloat sd_frustum(vec3v p, float4 a, float4 b, float radius_a, float radius_b) {
  float4 ba = b - a;
  float rba = radius_b - radius_a;
  float baba = dot(ba.xyz, ba.xyz);
  vec3v pa = v3_sub(p, v3_from(a));
  vfloat papa = v3_dot(pa, pa);
  vfloat t = v3_dot(pa, v3_from(ba)) / baba;
  vfloat x = vsqrt(fmax(papa - t * t * baba, 0.0f));
  vfloat cap_radius = select((vfloat)(radius_b), (vfloat)(radius_a), MASK(t < 0.5f));
  vfloat ca_x = fmax(x - cap_radius, 0.0f);
  vfloat ca_y = fabs(t - 0.5f) - 0.5f;
  float k = rba * rba + baba;
  vfloat f = clamp((rba * (x - radius_a) + t * baba) / k, 0.0f, 1.0f);
  vfloat cb_x = x - radius_a - f * rba;
  vfloat cb_y = t - f;
  vfloat s = select((vfloat)(1.0f), (vfloat)(-1.0f), MASK(cb_x < 0.0f) & MASK(ca_y < 0.0f));
  return s * vsqrt(fmin(ca_x * ca_x + ca_y * ca_y * baba, cb_x * cb_x + cb_y * cb_y * baba));
}

/* Exact (Inigo Quilez's sdCappedTorus, his xy plane laid on our xz): k is the distance along
 * the spine's plane to the nearest spine point's direction, the arc itself within angle of +z,
 * else the end's. The square's argument is clamped at 0: it is a squared distance that
 * rounding can take just below. */
SDF_INLINE vfloat sd_capped_torus(vec3v p, float4 center, float angle, float major_radius, float minor_radius) {
  vec3v l = v3_sub(p, v3_from(center));
  float s = sinpi(angle / 180.0f);
  float c = cospi(angle / 180.0f);
  vfloat x = fabs(l.x);
  vfloat k = select(vsqrt(x * x + l.z * l.z), x * s + l.z * c, MASK(c * x > s * l.z));
  vfloat squared = x * x + l.y * l.y + l.z * l.z + major_radius * major_radius - 2.0f * major_radius * k;
  return vsqrt(fmax(squared, 0.0f)) - minor_radius;
}

/* Exact (Inigo Quilez's sdLink): the torus about z, elongated along y by half_length. */
SDF_INLINE vfloat sd_link(vec3v p, float4 center, float half_length, float major_radius, float minor_radius) {
  vec3v l = v3_sub(p, v3_from(center));
  vfloat y = fmax(fabs(l.y) - half_length, 0.0f);
  vfloat ring = vsqrt(l.x * l.x + y * y) - major_radius;
  return vsqrt(ring * ring + l.z * l.z) - minor_radius;
}

/* Exact (Inigo Quilez's sdCutSphere): the part y >= cut_height of the ball, in the half plane
 * (r, y); w is the rim's radius. s < 0 picks the sphere; else the flat disc within the rim, or
 * the rim itself. */
SDF_INLINE vfloat sd_cut_sphere(vec3v p, float4 center, float radius, float cut_height) {
  vec3v l = v3_sub(p, v3_from(center));
  float h = cut_height;
  float w = sqrt(radius * radius - h * h);
  vfloat qx = vsqrt(l.x * l.x + l.z * l.z);
  vfloat qy = l.y;
  vfloat s = fmax((h - radius) * qx * qx + w * w * (h + radius - 2.0f * qy), h * qx - w * qy);
  vfloat sphere = vsqrt(qx * qx + qy * qy) - radius;
  vfloat rim = vsqrt((qx - w) * (qx - w) + (qy - h) * (qy - h));
  return select(select(rim, h - qy, MASK(qx < w)), sphere, MASK(s < 0.0f));
}

/* Exact: Inigo Quilez's sdPyramid for a base of side 1, scaled by 2 half_width, with the base
 * square added (his measures the side faces alone, too far below the base). Folded into the
 * octant x >= z >= 0 and measured to the face there and its edges; m2 is the squared length of
 * the face's slope vector (height, 1/2). */
SDF_INLINE vfloat sd_pyramid(vec3v p, float4 center, float half_width, float height) {
  float side = 2.0f * half_width;
  float h = height / side;
  float m2 = h * h + 0.25f;
  vec3v l = v3_scale(v3_sub(p, v3_from(center)), (vfloat)(1.0f / side));
  vfloat ax = fabs(l.x);
  vfloat az = fabs(l.z);
  vint swap = MASK(az > ax);
  vfloat px = select(ax, az, swap) - 0.5f;
  vfloat pz = select(az, ax, swap) - 0.5f;
  vfloat py = l.y;
  vfloat qx = pz;
  vfloat qy = h * py - 0.5f * px;
  vfloat qz = h * px + 0.5f * py;
  vfloat s = fmax(-qx, 0.0f);
  vfloat t = clamp((qy - 0.5f * pz) / (m2 + 0.25f), 0.0f, 1.0f);
  vfloat a = m2 * (qx + s) * (qx + s) + qy * qy;
  vfloat b = m2 * (qx + 0.5f * t) * (qx + 0.5f * t) + (qy - m2 * t) * (qy - m2 * t);
  vfloat d2 = select(fmin(a, b), (vfloat)(0.0f), MASK(fmin(qy, -qx * m2 - qy * 0.5f) > 0.0f));
  /* Quilez's measures the nearest side face only, which below the base overestimates: the base
   * square is the other candidate, outside to the square, inside to its plane. */
  vfloat bx = fmax(px, 0.0f);
  vfloat bz = fmax(pz, 0.0f);
  vfloat outside = fmin(vsqrt((d2 + qz * qz) / m2), vsqrt(bx * bx + bz * bz + py * py));
  vfloat inside = fmax(qz / sqrt(m2), -py);
  return side * select(outside, inside, MASK(qz < 0.0f) & MASK(py > 0.0f));
}

/* The squared distance from the point pa (relative to an edge's start) to the edge e. */
SDF_INLINE vfloat edge_distance2(vec3v pa, float4 e) {
  vfloat t = clamp(v3_dot(pa, v3_from(e)) / dot(e.xyz, e.xyz), 0.0f, 1.0f);
  vec3v off = v3_sub(v3_scale(v3_from(e), t), pa);
  return v3_dot(off, off);
}

/* 1 where the point pa (relative to an edge's start) is inside the edge e of a face of normal
 * n, -1 outside, 0 on its line. */
SDF_INLINE vfloat edge_side(vec3v pa, float4 e, float4 n) { return sign(v3_dot(v3_from(cross(e, n)), pa)); }

/* Exact (Inigo Quilez's udTriangle, thickened): the plane's distance where p projects inside
 * all three edges, else the nearest edge's. */
SDF_INLINE vfloat sd_triangle(vec3v p, float4 a, float4 b, float4 c, float thickness) {
  float4 ba = b - a;
  float4 cb = c - b;
  float4 ac = a - c;
  float4 n = cross(ba, ac);
  vec3v pa = v3_sub(p, v3_from(a));
  vec3v pb = v3_sub(p, v3_from(b));
  vec3v pc = v3_sub(p, v3_from(c));
  vfloat sides = edge_side(pa, ba, n) + edge_side(pb, cb, n) + edge_side(pc, ac, n);
  vfloat edges = fmin(fmin(edge_distance2(pa, ba), edge_distance2(pb, cb)), edge_distance2(pc, ac));
  vfloat plane = v3_dot(v3_from(n), pa);
  return vsqrt(select(plane * plane / dot(n.xyz, n.xyz), edges, MASK(sides < 2.0f))) - thickness;
}

/* Exact (Inigo Quilez's udQuad, thickened) for a planar convex quadrilateral. */
SDF_INLINE vfloat sd_quad(vec3v p, float4 a, float4 b, float4 c, float4 d, float thickness) {
  float4 ba = b - a;
  float4 cb = c - b;
  float4 dc = d - c;
  float4 ad = a - d;
  float4 n = cross(ba, ad);
  vec3v pa = v3_sub(p, v3_from(a));
  vec3v pb = v3_sub(p, v3_from(b));
  vec3v pc = v3_sub(p, v3_from(c));
  vec3v pd = v3_sub(p, v3_from(d));
  vfloat sides = edge_side(pa, ba, n) + edge_side(pb, cb, n) + edge_side(pc, dc, n) + edge_side(pd, ad, n);
  vfloat edges =
      fmin(fmin(edge_distance2(pa, ba), edge_distance2(pb, cb)), fmin(edge_distance2(pc, dc), edge_distance2(pd, ad)));
  vfloat plane = v3_dot(v3_from(n), pa);
  return vsqrt(select(plane * plane / dot(n.xyz, n.xyz), edges, MASK(sides < 3.0f))) - thickness;
}

/* A bound (Inigo Quilez's sdTriPrism): the largest signed distance to the two slanted sides
 * (normals (+-cos 30, sin 30)), the bottom side (inradius radius / 2) and the end caps. Below
 * the true distance near the edges outside. */
SDF_INLINE vfloat sd_triangular_prism(vec3v p, float4 center, float radius, float half_length) {
  vec3v l = v3_sub(p, v3_from(center));
  vfloat sides = fmax(fabs(l.x) * 0.8660254f + l.y * 0.5f, -l.y) - 0.5f * radius;
  return fmax(fabs(l.z) - half_length, sides);
}

/* Exact (Inigo Quilez's sdSolidAngle): in the half plane (r, y), l is the distance to the
 * circle, m to the sector's straight side (c its direction), signed by the side of it. */
SDF_INLINE vfloat sd_solid_angle(vec3v p, float4 center, float angle, float radius) {
  vec3v l = v3_sub(p, v3_from(center));
  float s = sinpi(angle / 180.0f);
  float c = cospi(angle / 180.0f);
  vfloat qx = vsqrt(l.x * l.x + l.z * l.z);
  vfloat qy = l.y;
  vfloat circle = vsqrt(qx * qx + qy * qy) - radius;
  vfloat t = clamp(qx * s + qy * c, 0.0f, radius);
  vfloat mx = qx - s * t;
  vfloat my = qy - c * t;
  return fmax(circle, vsqrt(mx * mx + my * my) * sign(c * qx - s * qy));
}

/* Exact (Inigo Quilez's sdCutHollowSphere): above the line from the centre through the rim
 * (w, cut_height) the rim is nearest, below it the sphere. */
SDF_INLINE vfloat sd_cut_hollow_sphere(vec3v p, float4 center, float radius, float cut_height, float thickness) {
  vec3v l = v3_sub(p, v3_from(center));
  float h = cut_height;
  float w = sqrt(radius * radius - h * h);
  vfloat qx = vsqrt(l.x * l.x + l.z * l.z);
  vfloat qy = l.y;
  vfloat rim = vsqrt((qx - w) * (qx - w) + (qy - h) * (qy - h));
  vfloat shell = fabs(vsqrt(qx * qx + qy * qy) - radius);
  return select(shell, rim, MASK(h * qx < w * qy)) - thickness;
}

/* Exact (Inigo Quilez's sdDeathStar, carved along +x): (a, b) is the circle where the spheres
 * meet, in the half plane (x, distance from the x axis); within the cone of the centre and that
 * circle, beyond it, the circle is nearest. */
SDF_INLINE vfloat sd_death_star(vec3v p, float4 center, float radius, float carve_radius, float carve_distance) {
  vec3v l = v3_sub(p, v3_from(center));
  float d = carve_distance;
  float a = (radius * radius - carve_radius * carve_radius + d * d) / (2.0f * d);
  float b = sqrt(radius * radius - a * a);
  vfloat px = l.x;
  vfloat py = vsqrt(l.y * l.y + l.z * l.z);
  vfloat rim = vsqrt((px - a) * (px - a) + (py - b) * (py - b));
  vfloat body = fmax(vsqrt(px * px + py * py) - radius, carve_radius - vsqrt((px - d) * (px - d) + py * py));
  return select(body, rim, MASK(px * b - py * a > d * fmax(b - py, 0.0f)));
}

/* Exact (Inigo Quilez's sdRhombus): in the quarter x, z >= 0 the nearest point of the side from
 * (half_width, 0) to (0, half_depth) is at f in [-1, 1] along it; signed by the side's line,
 * grown by corner_radius, then extruded along y. */
SDF_INLINE vfloat sd_rhombus(vec3v p, float4 center, float half_width, float half_depth, float half_height,
                             float corner_radius) {
  vec3v a = v3_abs(v3_sub(p, v3_from(center)));
  float la = half_width;
  float lb = half_depth;
  vfloat f = clamp((la * (la - 2.0f * a.x) - lb * (lb - 2.0f * a.z)) / (la * la + lb * lb), -1.0f, 1.0f);
  vfloat ex = a.x - 0.5f * la * (1.0f - f);
  vfloat ez = a.z - 0.5f * lb * (1.0f + f);
  vfloat qx = vsqrt(ex * ex + ez * ez) * sign(a.x * lb + a.z * la - la * lb) - corner_radius;
  vfloat qy = a.y - half_height;
  vfloat outside_x = fmax(qx, 0.0f);
  vfloat outside_y = fmax(qy, 0.0f);
  return fmin(fmax(qx, qy), 0.0f) + vsqrt(outside_x * outside_x + outside_y * outside_y);
}
