/* Combinators of distances (Inigo Quilez's polynomial smooth minimum). The hard ones are exact
 * outside for union and bounds otherwise; the smooth ones are bounds. The *_blend functions give
 * the weight h that the color blending of smooth operators shares with the distance. */

SDF_INLINE vfloat op_union(vfloat a, vfloat b) { return fmin(a, b); }
SDF_INLINE vfloat op_intersection(vfloat a, vfloat b) { return fmax(a, b); }
/* a minus b. */
SDF_INLINE vfloat op_subtraction(vfloat a, vfloat b) { return fmax(a, -b); }

SDF_INLINE vfloat smooth_union_blend(vfloat a, vfloat b, float k) {
  return clamp(0.5f + 0.5f * (b - a) / k, 0.0f, 1.0f);
}
SDF_INLINE vfloat smooth_intersection_blend(vfloat a, vfloat b, float k) {
  return clamp(0.5f - 0.5f * (b - a) / k, 0.0f, 1.0f);
}
SDF_INLINE vfloat smooth_subtraction_blend(vfloat a, vfloat b, float k) {
  return clamp(0.5f - 0.5f * (a + b) / k, 0.0f, 1.0f);
}

/* The id channel's number where a smooth operator blends two operands: y's where the weight h
 * of y is at least a half, else x's (numbers are not mixed). */
SDF_INLINE vfloat id_mix(vfloat x, vfloat y, vfloat h) { return select(x, y, MASK(h >= 0.5f)); }

SDF_INLINE vfloat op_smooth_union(vfloat a, vfloat b, float k) {
  vfloat h = smooth_union_blend(a, b, k);
  return mix(b, a, h) - k * h * (1.0f - h);
}
SDF_INLINE vfloat op_smooth_intersection(vfloat a, vfloat b, float k) {
  vfloat h = smooth_intersection_blend(a, b, k);
  return mix(b, a, h) + k * h * (1.0f - h);
}
/* a minus b. */
SDF_INLINE vfloat op_smooth_subtraction(vfloat a, vfloat b, float k) {
  vfloat h = smooth_subtraction_blend(a, b, k);
  return mix(a, -b, h) + k * h * (1.0f - h);
}

/* A lower bound of a subtree's field from its bounding sphere (host/scene/scene_bounds.hpp: the
 * field falls below tau only within radius + gain * tau of the centre), so (|p - c| - radius) / gain.
 * The generated map() skips a subtree whose bound shows it cannot change the operator's result. */
SDF_INLINE vfloat sd_bound(vec3v p, float4 center, float radius, float inverse_gain) {
  return (v3_length(v3_sub(p, v3_from(center))) - radius) * inverse_gain;
}

/* Centred domain repetition along one axis (IQ's opRep, floor-based like GLSL mod): the
 * coordinate inside its cell, in [-period/2, period/2). The distance stays a bound only while the
 * child fits inside the cell. */
SDF_INLINE vfloat op_repeat_axis(vfloat x, float period) { return x - period * floor(x / period + 0.5f); }

/* Crum's displacement texture amplitude * sin(f x) sin(f y) sin(f z) of the absolute point p +
 * offset, as sin(f p + phase) with phase = f offset mod 2 pi taken on the host in double
 * (host/codegen/sdf_codegen.cpp), so that far from the origin the texture keeps the precision of
 * the small p of map()'s frame rather than float's spacing of the absolute point. */
SDF_INLINE vfloat displacement(vec3v p, float4 phase, float amplitude, float frequency) {
  return amplitude * vsin(frequency * p.x + phase.x) * vsin(frequency * p.y + phase.y) *
         vsin(frequency * p.z + phase.z);
}

/* Polar repetition about the y axis (Inigo Quilez's and Mercury's pModPolar): p turned by the
 * multiple of sector nearest to its own angle, so that every copy k (at angle k * sector) is
 * measured as the child itself, k = 0. A bound only while the child fits inside its sector. */
SDF_INLINE vec3v op_repeat_polar(vec3v p, float sector) {
  vfloat turn = sector * round(atan2(p.z, p.x) / sector);
  vfloat c = vcos(turn);
  vfloat s = vsin(turn);
  return v3(c * p.x + s * p.z, p.y, c * p.z - s * p.x);
}

/* Limited repetition along one axis (Inigo Quilez's opLimitedRepetition): the copy at
 * period * i for the integer i in [first, last] nearest to x. */
SDF_INLINE vfloat op_repeat_limited_axis(vfloat x, float period, float first, float last) {
  return x - period * clamp(round(x / period), first, last);
}

/* Twist: p turned (right-handed) about the y axis by the angle rate * y. */
SDF_INLINE vec3v op_twist(vec3v p, float rate) {
  const vfloat c = vcos(rate * p.y), s = vsin(rate * p.y);
  return v3(c * p.x + s * p.z, p.y, c * p.z - s * p.x);
}

/* Bend: p turned (right-handed) about the z axis by the angle rate * x. */
SDF_INLINE vec3v op_bend(vec3v p, float rate) {
  const vfloat c = vcos(rate * p.x), s = vsin(rate * p.x);
  return v3(c * p.x - s * p.y, s * p.x + c * p.y, p.z);
}

/* The largest stretch of the twist's map at distance r from its axis, its Jacobian's largest
 * singular value (a + sqrt(a^2 + 4)) / 2 with a = |rate| r; reach is the child's from the axis.
 * On the segment from p to the nearest surface point no point is farther from the axis than
 * max(r, reach), so the child's distance divided by this is a bound. */
SDF_INLINE vfloat op_twist_lipschitz(vfloat r, float rate, float reach) {
  const vfloat a = fabs(rate) * fmax(r, reach);
  return 0.5f * (a + vsqrt(a * a + 4.0f));
}

/* Bend's factor as twist's: its Jacobian is a turn times I + u e_x^T with |u| = |rate| r (r the
 * distance from the z axis), whose largest singular value is at most 1 + |rate| r. */
SDF_INLINE vfloat op_bend_lipschitz(vfloat r, float rate, float reach) { return 1.0f + fabs(rate) * fmax(r, reach); }

/* Extrusion of a section's distance along z to |z| <= half_length (Quilez's opExtrusion): exact
 * where the section's distance is. */
SDF_INLINE vfloat op_extrude(vfloat section, vfloat z, float half_length) {
  const vfloat across = fabs(z) - half_length;
  const vfloat out_x = fmax(section, 0.0f), out_z = fmax(across, 0.0f);
  return fmin(fmax(section, across), 0.0f) + vsqrt(out_x * out_x + out_z * out_z);
}
