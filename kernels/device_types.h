/* Everything that crosses from the host to the device: one definition, included by the C++ host
 * and by the OpenCL C kernels. Fields are 4-byte scalars and float4s with explicit padding, so the
 * layout is the same on both sides (never glm::vec3 against OpenCL float3); the camera's doubles
 * come last, at an 8-byte boundary. */
#ifndef CLMARCH_DEVICE_TYPES_H
#define CLMARCH_DEVICE_TYPES_H

#ifndef __OPENCL_VERSION__
#include <CL/cl_platform.h>

#include <stddef.h>
typedef cl_float4 float4;
#define CLMARCH_INT cl_int
#define CLMARCH_FLOAT cl_float
#define CLMARCH_DOUBLE cl_double
#else
#define CLMARCH_INT int
#define CLMARCH_FLOAT float
/* 8 bytes the host wrote as a double: read with as_double() (double programs only, which enable
 * cl_khr_fp64; a float program never reads them and so needs no double type). */
#define CLMARCH_DOUBLE long
#endif

/* Planes of the output buffer, in the order of the --buffers EXR channels. */
#define CLMARCH_CHANNEL_R 0
#define CLMARCH_CHANNEL_G 1
#define CLMARCH_CHANNEL_B 2
#define CLMARCH_CHANNEL_DEPTH 3
#define CLMARCH_CHANNEL_STEPS 4
#define CLMARCH_CHANNEL_NX 5
#define CLMARCH_CHANNEL_NY 6
#define CLMARCH_CHANNEL_NZ 7
/* Not an EXR channel: the wall steps of the tiling's cell traversal, part of steps. */
#define CLMARCH_CHANNEL_WALL_STEPS 8
/* The number of the primitive a ray hit (host/scene/scene.hpp, primitive_count), -1 on a miss. */
#define CLMARCH_CHANNEL_ID 9
/* The shading's layers (WRITE_LAYERS), each r, g, b in three planes from its first: the ambient
 * light the occlusion leaves, the lights' diffuse and their specular reflection, as they reach
 * the camera through the fog, before tone mapping (kernels/shading.cl, LightTerms). */
#define CLMARCH_CHANNEL_AO 10
#define CLMARCH_CHANNEL_DIFFUSE 13
#define CLMARCH_CHANNEL_SPECULAR 16
/* The depth's remainder past its float, t - (float)t, in double programs' --buffers (WRITE_DEPTH_LO):
 * depth + depth.lo, added in double, is the depth the march found. */
#define CLMARCH_CHANNEL_DEPTH_LO 19
/* How each centre ray ended (CLMARCH_RAY_*), with WRITE_STATUS: --buffers, debug views, --stats. */
#define CLMARCH_CHANNEL_STATUS 20
#define CLMARCH_CHANNEL_COUNT 21

/* The status channel's values: a ray hit; missed (left the scene's bounding sphere, or never met
 * it); ran out of render.max_steps before either; or missed by reaching render.max_distance. */
#define CLMARCH_RAY_MISS 0
#define CLMARCH_RAY_HIT 1
#define CLMARCH_RAY_OUT_OF_STEPS 2
#define CLMARCH_RAY_OUT_OF_DISTANCE 3

/* Columns of the tile a packet of `lanes` pixels covers (its rows: lanes / columns): 1x1, 2x2,
 * 4x2, 4x4. The host plans its dispatch of tiles by it (host/render/dispatch_plan.hpp). */
#define CLMARCH_PACKET_WIDTH(lanes) ((lanes) == 1 ? 1 : (lanes) == 4 ? 2 : 4)

/* Pixels per side of a block of the coarse cone pass (kernels/coarse.cl), and the blocks that
 * cover n pixels (the last one cut by the image's edge). */
#define CLMARCH_COARSE_BLOCK 8
#define CLMARCH_COARSE_BLOCKS(n) (((n) + CLMARCH_COARSE_BLOCK - 1) / CLMARCH_COARSE_BLOCK)

/* The operand grid of a large union (host/prune/operand_grid.hpp, kernels/operand_grid.cl): its
 * header at the start of the scene data (SCENE_DATA), float words; the _AT words hold int offsets
 * into the scene data (bit patterns, read with as_int). The cells are a CSR index into the list:
 * cell c lists the words list[cells[c]] .. list[cells[c + 1] - 1], each the offset of an operand's
 * record: its distance shape, its color shape, the offset of its color literals, the number of its
 * first primitive (the id channel's), then literals. */
#define CLMARCH_GRID_ORIGIN 0       /* 3 words: the grid's lowest corner, in map()'s frame */
#define CLMARCH_GRID_INVERSE_CELL 3 /* 1 / the cells' side */
#define CLMARCH_GRID_DIMS 4         /* 3 words: cells per axis, as floats (at most 2^24 cells) */
#define CLMARCH_GRID_UPPER 7        /* 3 words: the grid's highest corner */
#define CLMARCH_GRID_OUTSIDE                            \
  10 /* 3 words: outside the grid the field is at least \
        (distance to the grid + [0]) * [1] - [2] */
#define CLMARCH_GRID_CELLS_AT 13
#define CLMARCH_GRID_LIST_AT 14
#define CLMARCH_GRID_HEADER_WORDS 15
#define CLMARCH_GRID_RECORD_ID 3    /* the word of a record holding its first primitive's number */
#define CLMARCH_GRID_RECORD_WORDS 4 /* distance shape, color shape, offset of the color literals, id */

/* Shadow rays (the SHADOW_MODE switch; host/scene/scene.hpp, ShadowMode, in the same order): hard
 * shadows, Inigo Quilez's classic penumbra min(k h / t), or his improved one. */
#define CLMARCH_SHADOW_HARD 0
#define CLMARCH_SHADOW_SOFT 1
#define CLMARCH_SHADOW_SOFT_IMPROVED 2

/* Kinds of light (host/scene/scene.hpp, LightKind, in the same order) and their falloffs (Falloff). */
#define CLMARCH_LIGHT_POINT 0
#define CLMARCH_LIGHT_DIRECTIONAL 1
#define CLMARCH_LIGHT_SPOT 2
#define CLMARCH_FALLOFF_NONE 0
#define CLMARCH_FALLOFF_INVERSE_SQUARE 1

/* One light. Positions are relative to the camera (computed on the host in double). */
typedef struct LightParams {
  float4 where;        /* point and spot lights: xyz = position; directional: xyz = unit vector towards the light */
  float4 radiance;     /* xyz = color * intensity */
  float4 spot_axis;    /* spot lights: xyz = unit vector the light points along */
  CLMARCH_INT kind;    /* CLMARCH_LIGHT_* */
  CLMARCH_INT falloff; /* CLMARCH_FALLOFF_* */
  CLMARCH_INT casts_shadows;    /* 1: shadow rays march towards it (with SHADOW_MODE) */
  CLMARCH_FLOAT inverse_range2; /* 1 / range^2 (the window clamp(1 - (d / range)^4, 0, 1)^2); 0: no range */
  CLMARCH_FLOAT cos_inner;      /* spot lights: cosines of the cone's inner and outer angles */
  CLMARCH_FLOAT cos_outer;
  CLMARCH_FLOAT padding[2];
} LightParams;

/* The shading's numbers (kernels/shading.cl, atmosphere.cl): host/scene/scene.hpp's Shading, as
 * floats. Which of them a program reads is its feature switches' choice (NEED_SHADING, FOG,
 * SKY, ...); the others are 0. Per frame, like the camera: changing them does not rebuild. */
typedef struct ShadingParams {
  float4 background;
  float4 ambient;
  float4 fog_color;
  float4 sky_horizon;
  float4 sky_zenith;
  float4 glow_color;
  float4 planet_glow_color;
  float4 planet_glow_sun; /* unit vector towards the sun */
  float4 height_fog_color;
  float4 height_fog_sun_color;
  float4 height_fog_sun_direction;
  CLMARCH_FLOAT diffuse;
  CLMARCH_FLOAT step_ao; /* steps^2 / step_ao darkens (STEP_AO) */
  CLMARCH_FLOAT fog_density;
  CLMARCH_FLOAT shadow_k; /* the soft penumbra's sharpness */
  CLMARCH_FLOAT shadow_min_t;
  CLMARCH_FLOAT shadow_max_t; /* directional lights' shadow rays end here */
  CLMARCH_FLOAT ao_step;
  CLMARCH_FLOAT ao_power;
  CLMARCH_FLOAT reflection_offset;
  CLMARCH_FLOAT glow_radius; /* also the cone pass's margin (kernels/coarse.cl): 0 without glow */
  CLMARCH_FLOAT planet_glow_sharpness;
  CLMARCH_FLOAT height_fog_density;
  CLMARCH_FLOAT height_fog_falloff;
  CLMARCH_FLOAT height_fog_sun_power;
  CLMARCH_FLOAT gamma;     /* DISPLAY_GAMMA: c^(1 / gamma) */
  CLMARCH_INT light_count; /* LightParams in the lights buffer */
  CLMARCH_INT shadow_max_steps;
  CLMARCH_INT ao_samples;
  CLMARCH_INT reflection_bounces;
  CLMARCH_INT padding[1];
} ShadingParams;

/* Floats from a refining pass's sample points' x to their y (kernels/march.cl, sample_packet):
 * kMaxSamples (host/scene/scene.hpp) and a vector's lanes past the last. */
#define CLMARCH_SAMPLE_POINT_STRIDE (1024 + 16)
/* float4s a refining pass writes for a run of one pixel's samples: the sum of their colors and
 * hits, then with the layers the sums of ao, diffuse and specular (kernels/march.cl, store_samples). */
#define CLMARCH_REFINED_FLOAT4S(layers) ((layers) ? 4 : 1)

/* Where each camera vector starts in MarchParams.camera_double: three doubles x, y, z. */
#define CLMARCH_CAMERA_ORIGIN 0
#define CLMARCH_CAMERA_FORWARD 3
#define CLMARCH_CAMERA_RIGHT 6
#define CLMARCH_CAMERA_UP 9
#define CLMARCH_CAMERA_ORIGIN_IN_CELL 12
#define CLMARCH_CAMERA_DOUBLES 16

/* Per-frame parameters: the camera contract's basis, the march limits and the shading's numbers.
 * Changing any of these does not rebuild the program; the program's #defines are only feature
 * switches (host/codegen/kernel_source.cpp). */
typedef struct MarchParams {
  float4 origin;         /* xyz = camera position relative to map_frame_origin (host/scene/camera_model.hpp) */
  float4 forward;        /* xyz = f, unit */
  float4 right_extent;   /* xyz = r * aspect * tan(fov / 2) */
  float4 up_extent;      /* xyz = u * tan(fov / 2) */
  float4 origin_in_cell; /* tiling (cells): xyz = camera offset inside its cell, 0 <= x < cell */
  float4 bounds;         /* xyz = camera position - centre of the sphere camera, shadow and mirror
                            rays are clipped to, w = its radius; w = 0: rays are not clipped */
  float4 tile_reach;     /* x = reach^2: a tile whose centre ray q (unnormalised) has
                            |c x q|^2 > reach^2 |q|^2 misses the bounds (kernels/march.cl); y, z, w = 0 */
  float4 sampling;       /* ANTIALIAS programs: x = 1 on a refining pass, which marches samples 1 ..
                            y - 1 (y = render.samples) of the z pixels of its refine_pixels instead
                            of tiles (kernels/march.cl, sample_packet); x = y = z = 0 on the centre
                            pass; w = 0 */
  float4 cell_bounds;    /* tiling (cells): xyz = centre, in the cell's frame, of the sphere holding
                            the cell's content (host/scene/scene_bounds.hpp, cell_bounds), w = its
                            radius; w = 0: none */
  float4 box_low;        /* xyz = the lowest corner of the box rays are clipped to besides the
                            sphere (host/scene/scene_box.hpp) less the camera position, w = 1; w = 0:
                            no box */
  float4 box_high;       /* xyz = its highest corner less the camera position; w = 0 */
  float4 bounds_gain;    /* x = the gain of the sphere (bounds), y = of the box: outside them the
                            field is at least the distance to them over their gain (soft shadows'
                            rays, kernels/shading.cl); z, w = 0 */
  CLMARCH_INT width;
  CLMARCH_INT height;
  CLMARCH_INT first_row;    /* first image row of this dispatch (images render in chunks of rows) */
  CLMARCH_INT chunk_rows;   /* rows per dispatch, a multiple of the packet height */
  CLMARCH_INT plane_stride; /* floats per output plane: chunk_rows * width */
  CLMARCH_INT max_steps;
  CLMARCH_FLOAT epsilon;
  CLMARCH_FLOAT max_distance;
  CLMARCH_FLOAT normal_epsilon;
  CLMARCH_FLOAT camera_height;   /* world y of the camera, for height fog */
  CLMARCH_FLOAT over_relaxation; /* camera rays' omega in [1, 2); 1 = plain sphere tracing */
  CLMARCH_FLOAT hit_cone_slope;  /* camera rays hit below max(epsilon, hit_cone_slope * t); 0 = fixed */
  /* With bounds: the image's tiles in columns live_columns[0] .. live_columns[1] and rows
     live_rows[0] .. live_rows[1] (both included) hold every tile whose rays may meet the sphere
     (host/render/live_tiles.cpp); the others miss it. */
  CLMARCH_INT live_columns[2];
  CLMARCH_INT live_rows[2];
  ShadingParams shading;
  /* origin, forward, right_extent, up_extent and origin_in_cell as the host's doubles
     (CLMARCH_CAMERA_*; the last double is padding): what double programs (render.precision: double)
     build their rays from, where float's rounding of the camera would move a deep zoom's view by
     pixels. */
  CLMARCH_DOUBLE camera_double[CLMARCH_CAMERA_DOUBLES];
} MarchParams;

#ifndef __OPENCL_VERSION__
static_assert(sizeof(LightParams) == 3 * 16 + 8 * 4, "LightParams layout must match OpenCL C");
static_assert(offsetof(LightParams, kind) == 3 * 16, "LightParams: the scalars after the float4s");
static_assert(sizeof(ShadingParams) == 11 * 16 + 20 * 4, "ShadingParams layout must match OpenCL C");
static_assert(offsetof(ShadingParams, diffuse) == 11 * 16, "ShadingParams: scalars after the float4s");
static_assert(sizeof(ShadingParams) % 16 == 0, "ShadingParams keeps the float4 alignment of what follows");
static_assert(offsetof(MarchParams, shading) == 12 * 16 + 16 * 4, "MarchParams: the shading after the march limits");
static_assert(sizeof(MarchParams) == 12 * 16 + 16 * 4 + sizeof(ShadingParams) + CLMARCH_CAMERA_DOUBLES * 8,
              "MarchParams layout must match OpenCL C");
static_assert(offsetof(MarchParams, camera_double) % 8 == 0, "doubles at 8-byte boundaries, as OpenCL C aligns them");
#endif

#endif
