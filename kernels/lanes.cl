/* Lane types: a work-item marches LANES pixels at once as explicit OpenCL vectors, so PoCL runs
 * them as SIMD (its implicit vectoriser gives up on data-dependent march loops); LANES = 1 is one
 * pixel per work-item, the natural shape on GPUs. Every kernel file is written against vfloat, vint
 * and vec3v so one source serves all widths. The pixels of a packet form a tile of PACKET_WIDTH x
 * PACKET_HEIGHT (4x4 for 16 lanes): neighbours in both directions take similar step counts, so
 * fewer lanes idle while the slowest ray of the packet finishes than with a row of 16.
 * Masks are 0 or -1 (all bits) at every width: vector comparisons already give -1, scalar ones
 * give 1, so scalar comparisons go through MASK(). */
/* The packet width must not change the image. NVIDIA's compiler fuses a * b + c differently in
 * scalar and vector code (1 and 16 lanes an epsilon of depth apart), so the host defines
 * NO_FP_CONTRACT for every device but PoCL, whose fused operations agree at every width and
 * would cost up to 10 % to forbid (allows_fp_contraction, docs/performance.md). */
#ifdef NO_FP_CONTRACT
#pragma OPENCL FP_CONTRACT OFF
#endif

#ifndef LANES
#define LANES 1
#endif

/* Clang notes that passing float16 in AVX registers differs from the AVX-512 calling convention.
 * Every call here is inlined inside one program, so no ABI boundary exists; the note is noise.
 * Older clangs (NVIDIA's OpenCL compiler) lack the group and would warn about the pragma itself. */
#if defined(__clang__) && defined(__has_warning)
#if __has_warning("-Wpsabi")
#pragma clang diagnostic ignored "-Wpsabi"
#endif
#endif

/* The lane scalar: float, or double with DOUBLE_PRECISION (cl_khr_fp64); REAL_EPSILON is its
 * machine epsilon. Masks have the width of the scalar (select() wants long masks for double).
 * Buffers stay float either way (STORE_LANES and LOAD_LANES convert, a no-op for float), except
 * eval_points' points and distances, `real` buffers that STORE_REAL_LANES fills: a double program's
 * field keeps its digits on the way to `clmarch field`. */
#ifdef DOUBLE_PRECISION
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
typedef double4 real4;
typedef double8 real8;
typedef double16 real16;
typedef long mask1;
typedef long4 mask4;
typedef long8 mask8;
typedef long16 mask16;
typedef long2 mask2;
#define convert_real convert_double
#define convert_real4 convert_double4
#define convert_real8 convert_double8
#define convert_real16 convert_double16
#define REAL_EPSILON DBL_EPSILON
#else
typedef float real;
typedef float4 real4;
typedef float8 real8;
typedef float16 real16;
typedef int mask1;
typedef int4 mask4;
typedef int8 mask8;
typedef int16 mask16;
typedef int2 mask2;
#define convert_real convert_float
#define convert_real4 convert_float4
#define convert_real8 convert_float8
#define convert_real16 convert_float16
#define REAL_EPSILON FLT_EPSILON
#endif

#if LANES == 1
typedef real vfloat;
typedef mask1 vint;
#define MASK(c) (-(vint)(c))
#define LANE_ANY(m) ((m) != 0)
#define LANE_IOTA 0
#define LANE_X 0
#define LANE_Y 0
#define TO_VFLOAT(x) convert_real(x)
#define STORE_LANES(v, base, ptr) ((ptr)[base] = (float)(v))
#define STORE_REAL_LANES(v, base, ptr) ((ptr)[base] = (v))
#define ROUNDED_TO_FLOAT(v) ((real)(float)(v))
#define STORE_INT_LANES(v, base, ptr) ((ptr)[base] = (int)(v))
#define LOAD_LANES(base, ptr) convert_real((ptr)[base])
#elif LANES == 4
typedef real4 vfloat;
typedef mask4 vint;
#define MASK(c) (c)
#define LANE_ANY(m) any(m)
#define LANE_IOTA ((vint)(0, 1, 2, 3))
#define LANE_X ((vint)(0, 1, 0, 1))
#define LANE_Y ((vint)(0, 0, 1, 1))
#define TO_VFLOAT(x) convert_real4(x)
#define VSTORE_LANES vstore4
#define VLOAD_LANES vload4
#define STORE_LANES(v, base, ptr) vstore4(convert_float4(v), 0, (ptr) + (base))
#define STORE_REAL_LANES(v, base, ptr) vstore4((v), 0, (ptr) + (base))
#define ROUNDED_TO_FLOAT(v) convert_real4(convert_float4(v))
#define STORE_INT_LANES(v, base, ptr) vstore4(convert_int4(v), 0, (ptr) + (base))
#define LOAD_LANES(base, ptr) convert_real4(vload4(0, (ptr) + (base)))
#elif LANES == 8
typedef real8 vfloat;
typedef mask8 vint;
#define MASK(c) (c)
#define LANE_ANY(m) any(m)
#define LANE_IOTA ((vint)(0, 1, 2, 3, 4, 5, 6, 7))
#define LANE_X ((vint)(0, 1, 2, 3, 0, 1, 2, 3))
#define LANE_Y ((vint)(0, 0, 0, 0, 1, 1, 1, 1))
#define TO_VFLOAT(x) convert_real8(x)
#define VSTORE_LANES vstore8
#define VLOAD_LANES vload8
#define STORE_LANES(v, base, ptr) vstore8(convert_float8(v), 0, (ptr) + (base))
#define STORE_REAL_LANES(v, base, ptr) vstore8((v), 0, (ptr) + (base))
#define ROUNDED_TO_FLOAT(v) convert_real8(convert_float8(v))
#define STORE_INT_LANES(v, base, ptr) vstore8(convert_int8(v), 0, (ptr) + (base))
#define LOAD_LANES(base, ptr) convert_real8(vload8(0, (ptr) + (base)))
#elif LANES == 16
typedef real16 vfloat;
typedef mask16 vint;
#define MASK(c) (c)
#define LANE_ANY(m) any16(m)
#define LANE_IOTA ((vint)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#define LANE_X ((vint)(0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3))
#define LANE_Y ((vint)(0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3))
#define TO_VFLOAT(x) convert_real16(x)
#define VSTORE_LANES vstore16
#define VLOAD_LANES vload16
#define STORE_LANES(v, base, ptr) vstore16(convert_float16(v), 0, (ptr) + (base))
#define STORE_REAL_LANES(v, base, ptr) vstore16((v), 0, (ptr) + (base))
#define ROUNDED_TO_FLOAT(v) convert_real16(convert_float16(v))
#define STORE_INT_LANES(v, base, ptr) vstore16(convert_int16(v), 0, (ptr) + (base))
#define LOAD_LANES(base, ptr) convert_real16(vload16(0, (ptr) + (base)))
#else
#error "LANES must be 1, 4, 8 or 16"
#endif
#define PACKET_WIDTH CLMARCH_PACKET_WIDTH(LANES)
#define PACKET_HEIGHT (LANES / PACKET_WIDTH)

/* Stores lane vector v into the private array a of LANES elements of its own type. */
#if LANES == 1
#define STORE_PRIVATE(v, a) ((a)[0] = (v))
#else
#define STORE_PRIVATE(v, a) VSTORE_LANES((v), 0, (a))
#endif

/* Stores a packet's lanes as the rows of its tile: row r at ptr + at + r * width. */
#if LANES == 1
#define STORE_TILE(v, at, width, ptr) ((ptr)[at] = (float)(v))
#elif LANES == 4
#define STORE_TILE(v, at, width, ptr) \
  (vstore2(convert_float2((v).s01), 0, (ptr) + (at)), vstore2(convert_float2((v).s23), 0, (ptr) + (at) + (width)))
#elif LANES == 8
#define STORE_TILE(v, at, width, ptr) \
  (vstore4(convert_float4((v).lo), 0, (ptr) + (at)), vstore4(convert_float4((v).hi), 0, (ptr) + (at) + (width)))
#else
#define STORE_TILE(v, at, width, ptr)                                                                                  \
  (vstore4(convert_float4((v).s0123), 0, (ptr) + (at)), vstore4(convert_float4((v).s4567), 0, (ptr) + (at) + (width)), \
   vstore4(convert_float4((v).s89ab), 0, (ptr) + (at) + 2 * (width)),                                                  \
   vstore4(convert_float4((v).scdef), 0, (ptr) + (at) + 3 * (width)))
#endif

/* Square roots and transcendentals of the distance functions and normals: the precise builtins,
 * or with NATIVE_MATH the native_* ones (PoCL maps native_sin/cos to SLEEF's 3.5-ulp vector
 * routines; the plain builtins are correctly rounded or 1-4 ulp). OpenCL has native_* for float
 * only, so the host never sets NATIVE_MATH with DOUBLE_PRECISION. acos and atan2 have no native
 * form. native_powr needs x >= 0, which every caller guarantees (radii). */
#ifdef NATIVE_MATH
#define vsqrt native_sqrt
#define vrsqrt native_rsqrt
#define vsin native_sin
#define vcos native_cos
#define vlog native_log
#define vpow native_powr
#else
#define vsqrt sqrt
#define vrsqrt rsqrt
#define vsin sin
#define vcos cos
#define vlog log
#define vpow pow
#endif

/* Functions of the distance field must inline into the march loop: a call that is not inlined
 * stops vectorisation. */
#define SDF_INLINE static inline __attribute__((always_inline))

/* The kernels' stages — a march loop, a normal, a shadow ray, the shading of a hit, the material at
 * a hit — are functions called, not inlined, where the host asks (STAGES_CALLED, render.stages) and
 * a work-item marches a packet. Inlined, map() comes into the one kernel function once per place
 * that evaluates the field (a 20-primitive scene: 14 copies in 2,600 lines) and PoCL's compile
 * grows faster than the function does: that scene's first picture took 5.0 s of CPU inlined, 1.8 s
 * staged. A call costs a small map a tenth of its time and more (inlined, the normal's taps share
 * their work), so the host calls the stages of large maps only (docs/performance.md). A
 * work-item's lanes are one vector, so a call does not stop their vectorisation; one pixel per
 * work-item relies on PoCL's vectoriser across work-items, which a call stops. */
#if LANES > 1 && defined(STAGES_CALLED)
#define SDF_STAGE static __attribute__((noinline))
#else
#define SDF_STAGE SDF_INLINE
#endif

/* A stage that every program with packets calls: the mirror bounces, which repeat the hit's
 * shading (normal, material, shadow rays, occlusion) after a march of their own, doubling the
 * kernel function; called, the two compile as halves (spheres repeated over a floor with two
 * bounces: 2.65 s to the first picture inlined, 2.27 s; lava_lamp 3.5 s, 2.5 s), and the call
 * costs each bounce nothing beside its march. */
#if LANES > 1
#define SDF_CALLED static __attribute__((noinline))
#else
#define SDF_CALLED SDF_INLINE
#endif

/* Whether any of 16 lanes is set, as an OR tree: PoCL 3.1's any() tests the lanes one by one with
 * a branch each, which cost the torus's march loop about 10 % (measured). */
#if LANES == 1 && defined(DOUBLE_PRECISION)
/* One double lane (GPUs' shape): the kernels pass float literals to builtins (fmax(x, 0.0f)),
 * which for a scalar double x match the float and the double overloads alike. These take every
 * argument as double; their bodies call the builtins before the names are redefined. */
SDF_INLINE double lane_fmax(double a, double b) { return fmax(a, b); }
SDF_INLINE double lane_fmin(double a, double b) { return fmin(a, b); }
SDF_INLINE double lane_clamp(double x, double low, double high) { return clamp(x, low, high); }
SDF_INLINE double lane_mix(double a, double b, double t) { return mix(a, b, t); }
SDF_INLINE double lane_step(double edge, double x) { return step(edge, x); }
SDF_INLINE double lane_smoothstep(double low, double high, double x) { return smoothstep(low, high, x); }
SDF_INLINE double lane_pow(double x, double y) { return pow(x, y); }
SDF_INLINE double lane_atan2(double y, double x) { return atan2(y, x); }
SDF_INLINE double lane_copysign(double x, double y) { return copysign(x, y); }
#undef fmax
#undef fmin
#undef clamp
#undef mix
#undef step
#undef smoothstep
#undef pow
#undef atan2
#undef copysign
#define fmax(a, b) lane_fmax((a), (b))
#define fmin(a, b) lane_fmin((a), (b))
#define clamp(x, low, high) lane_clamp((x), (low), (high))
#define mix(a, b, t) lane_mix((a), (b), (t))
#define step(edge, x) lane_step((edge), (x))
#define smoothstep(low, high, x) lane_smoothstep((low), (high), (x))
#define pow(x, y) lane_pow((x), (y))
#define atan2(y, x) lane_atan2((y), (x))
#define copysign(x, y) lane_copysign((x), (y))
#endif

SDF_INLINE int any16(mask16 m) {
  const mask8 a = m.lo | m.hi;
  const mask4 b = a.lo | a.hi;
  const mask2 c = b.lo | b.hi;
  return (c.x | c.y) < 0;
}

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
SDF_INLINE vec3v v3_cross(vec3v a, vec3v b) {
  return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
/* sqrt(dot) rather than length(): PoCL's length() carries overflow-rescaling branches. */
SDF_INLINE vfloat v3_length(vec3v a) { return vsqrt(v3_dot(a, a)); }
SDF_INLINE vfloat v3_max_component(vec3v a) { return fmax(a.x, fmax(a.y, a.z)); }
/* A zero vector stays zero instead of becoming NaN. */
SDF_INLINE vec3v v3_normalize(vec3v a) {
  vfloat len2 = v3_dot(a, a);
  return v3_scale(a, select((vfloat)(0.0f), vrsqrt(len2), MASK(len2 > 0.0f)));
}
SDF_INLINE vec3v v3_select(vec3v a, vec3v b, vint m) {
  return v3(select(a.x, b.x, m), select(a.y, b.y, m), select(a.z, b.z, m));
}
SDF_INLINE vec3v v3_mix(vec3v a, vec3v b, vfloat h) { return v3(mix(a.x, b.x, h), mix(a.y, b.y, h), mix(a.z, b.z, h)); }
/* Rows of a 3x3 matrix times a vector. */
SDF_INLINE vec3v v3_transform(vec3v p, float m00, float m01, float m02, float m10, float m11, float m12, float m20,
                              float m21, float m22) {
  return v3(m00 * p.x + m01 * p.y + m02 * p.z, m10 * p.x + m11 * p.y + m12 * p.z, m20 * p.x + m21 * p.y + m22 * p.z);
}
