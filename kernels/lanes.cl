/* Lane types: a work-item marches LANES pixels at once as explicit OpenCL vectors, so PoCL runs
 * them as SIMD (its implicit vectoriser gives up on data-dependent march loops); LANES = 1 is one
 * pixel per work-item, the natural shape on GPUs. Every kernel file is written against vfloat, vint
 * and vec3v so one source serves all widths.
 * Masks are 0 or -1 (all bits) at every width: vector comparisons already give -1, scalar ones
 * give 1, so scalar comparisons go through MASK(). */
#ifndef LANES
#define LANES 1
#endif

#ifdef __clang__
/* Clang notes that passing float16 in AVX registers differs from the AVX-512 calling convention.
 * Every call here is inlined inside one program, so no ABI boundary exists; the note is noise. */
#pragma clang diagnostic ignored "-Wpsabi"
#endif

#if LANES == 1
typedef float vfloat;
typedef int vint;
#define MASK(c) (-(int)(c))
#define LANE_ANY(m) ((m) != 0)
#define LANE_IOTA 0
#define TO_VFLOAT(x) ((float)(x))
#define STORE_LANES(v, base, ptr) ((ptr)[base] = (v))
#define LOAD_LANES(base, ptr) ((ptr)[base])
#elif LANES == 4
typedef float4 vfloat;
typedef int4 vint;
#define MASK(c) (c)
#define LANE_ANY(m) any(m)
#define LANE_IOTA ((int4)(0, 1, 2, 3))
#define TO_VFLOAT(x) convert_float4(x)
#define STORE_LANES(v, base, ptr) vstore4((v), 0, (ptr) + (base))
#define LOAD_LANES(base, ptr) vload4(0, (ptr) + (base))
#elif LANES == 8
typedef float8 vfloat;
typedef int8 vint;
#define MASK(c) (c)
#define LANE_ANY(m) any(m)
#define LANE_IOTA ((int8)(0, 1, 2, 3, 4, 5, 6, 7))
#define TO_VFLOAT(x) convert_float8(x)
#define STORE_LANES(v, base, ptr) vstore8((v), 0, (ptr) + (base))
#define LOAD_LANES(base, ptr) vload8(0, (ptr) + (base))
#elif LANES == 16
typedef float16 vfloat;
typedef int16 vint;
#define MASK(c) (c)
#define LANE_ANY(m) any(m)
#define LANE_IOTA ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#define TO_VFLOAT(x) convert_float16(x)
#define STORE_LANES(v, base, ptr) vstore16((v), 0, (ptr) + (base))
#define LOAD_LANES(base, ptr) vload16(0, (ptr) + (base))
#else
#error "LANES must be 1, 4, 8 or 16"
#endif

/* Functions of the distance field must inline into the march loop: a call that is not inlined
 * stops vectorisation. */
#define SDF_INLINE static inline __attribute__((always_inline))

/* A point or direction per lane, as three lane vectors (structure of arrays). */
typedef struct {
  vfloat x, y, z;
} vec3v;

SDF_INLINE vec3v v3(vfloat x, vfloat y, vfloat z) {
  vec3v r = {x, y, z};
  return r;
}
/* Every lane the same point: a constant of the scene. */
SDF_INLINE vec3v v3_from(float4 a) { return v3((vfloat)(a.x), (vfloat)(a.y), (vfloat)(a.z)); }
SDF_INLINE vec3v v3_splat(float a) { return v3((vfloat)(a), (vfloat)(a), (vfloat)(a)); }
SDF_INLINE vec3v v3_add(vec3v a, vec3v b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
SDF_INLINE vec3v v3_sub(vec3v a, vec3v b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
SDF_INLINE vec3v v3_scale(vec3v a, vfloat s) { return v3(a.x * s, a.y * s, a.z * s); }
SDF_INLINE vec3v v3_mul(vec3v a, vec3v b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
SDF_INLINE vec3v v3_abs(vec3v a) { return v3(fabs(a.x), fabs(a.y), fabs(a.z)); }
SDF_INLINE vec3v v3_max0(vec3v a) { return v3(fmax(a.x, 0.0f), fmax(a.y, 0.0f), fmax(a.z, 0.0f)); }
SDF_INLINE vfloat v3_dot(vec3v a, vec3v b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
/* sqrt(dot) rather than length(): PoCL's length() carries overflow-rescaling branches. */
SDF_INLINE vfloat v3_length(vec3v a) { return sqrt(v3_dot(a, a)); }
SDF_INLINE vfloat v3_max_component(vec3v a) { return fmax(a.x, fmax(a.y, a.z)); }
/* A zero vector stays zero instead of becoming NaN. */
SDF_INLINE vec3v v3_normalize(vec3v a) {
  vfloat len2 = v3_dot(a, a);
  return v3_scale(a, select((vfloat)(0.0f), rsqrt(len2), MASK(len2 > 0.0f)));
}
SDF_INLINE vec3v v3_select(vec3v a, vec3v b, vint m) {
  return v3(select(a.x, b.x, m), select(a.y, b.y, m), select(a.z, b.z, m));
}
SDF_INLINE vec3v v3_mix(vec3v a, vec3v b, vfloat h) { return v3(mix(a.x, b.x, h), mix(a.y, b.y, h), mix(a.z, b.z, h)); }
/* Rows of a 3x3 matrix times a vector. */
SDF_INLINE vec3v v3_transform(vec3v p, float m00, float m01, float m02, float m10, float m11, float m12,
                              float m20, float m21, float m22) {
  return v3(m00 * p.x + m01 * p.y + m02 * p.z, m10 * p.x + m11 * p.y + m12 * p.z,
            m20 * p.x + m21 * p.y + m22 * p.z);
}
