// Assembles the OpenCL C program for one scene: feature switches, the kernels/ building blocks it
// needs (each behind a #line so build errors point at the real file), and the generated scene code.
#pragma once

#include "codegen/sdf_codegen.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace clmarch {

/// What the program is built for.
enum class KernelPurpose {
  /// The march kernel, writing depth and steps only.
  DepthSteps,
  /// The march kernel with normals (no shading).
  Normals,
  /// The march kernel with normals and the lit color.
  Shaded,
  /// Everything the --buffers EXR holds: the normals, the lit color, the primitive hit and the
  /// shading's layers.
  Buffers,
  /// The lit color without the normal planes (a color image alone: the shading still computes
  /// normals, the kernel does not store them).
  Color,
  /// The eval_points kernel (tests against closed forms).
  EvalPoints,
  /// The benchmark's ceiling: the depth-only march kernel recording every point it evaluates
  /// (RECORD_SAMPLES), and replay_samples, which evaluates those points densely.
  Ceiling,
};

/// Arithmetic variants of one program, which `clmarch bench --sweep` compares (docs/accuracy.md).
struct KernelVariant {
  Precision precision = Precision::Float;
  /// native_* square roots and transcendentals in the distance functions (NATIVE_MATH; float only).
  bool native_math = false;
  /// -cl-fast-relaxed-math in the build options.
  bool fast_math = false;

  bool operator==(const KernelVariant&) const = default;
};

struct KernelOptions {
  KernelOptions() = default;
  /// {purpose, lanes} keeps the default variant.
  KernelOptions(KernelPurpose what, int pixels_per_item, KernelVariant arithmetic = {})
      : purpose(what), lanes(pixels_per_item), variant(arithmetic) {}

  KernelPurpose purpose = KernelPurpose::Shaded;
  /// Pixels per work-item: 1, 4, 8 or 16.
  int lanes = 1;
  KernelVariant variant;
  /// Whether the compiler may fuse a * b + c (no NO_FP_CONTRACT); allows_fp_contraction(device).
  bool fp_contraction = true;
  /// Literals of march_scene_code(scene) that the program reads from its scene_values buffer
  /// (animations: VaryingLiterals); march programs only.
  ValueSlots value_slots;
  /// The status plane in every march program (march_outputs).
  bool ray_status = false;
};

/// What a march program computes beyond depth and steps, and so which planes of the output buffer
/// its kernel writes (kernels/march.cl; channel numbers of kernels/device_types.h).
struct MarchOutputs {
  bool normals = false;     ///< WRITE_NORMALS: N.x, N.y, N.z
  bool color = false;       ///< NEED_SHADING: R, G, B
  bool wall_steps = false;  ///< the cells tiling: wall steps
  bool ids = false;         ///< WRITE_IDS: the primitive hit (with the normals)
  bool layers = false;      ///< WRITE_LAYERS: ao, diffuse and specular (with the normals and the color)
  bool depth_lo = false;    ///< WRITE_DEPTH_LO: depth.lo (double programs' --buffers)
  bool status = false;      ///< WRITE_STATUS: how each ray ended (--buffers, debug views, --stats)

  /// The planes the kernel writes for every pixel of a dispatch; the others it never touches.
  std::vector<int> planes() const;
};
/// ray_status: the status plane also in programs that do not otherwise write it (Shaded, Color,
/// DepthSteps; render --stats counts the rays out of steps), at the cost of one more plane.
MarchOutputs march_outputs(const Scene& scene, KernelPurpose purpose, bool ray_status);

/// Whether the march program of purpose anti-aliases (ANTIALIAS: render.samples > 1; not the
/// benchmark's ceiling): its camera rays cross their pixels at MarchParams::sample, and it takes
/// the sample_mask, refine_packets and sample_points arguments of its refining pass (kernels/march.cl).
bool uses_antialiasing(const Scene& scene, KernelPurpose purpose);

/// Whether the program of scene, whose scene code (map, map_color and what they call) is code,
/// calls its stages rather than inlining them (render.stages; auto: code of at least
/// kCalledStagesChars characters, measured in docs/performance.md).
bool calls_stages(const Scene& scene, const SdfCode& code);
inline constexpr std::size_t kCalledStagesChars = 9000;

/// Packets each work-item of the march kernel marches (PACKETS_PER_ITEM): two, interleaved, with
/// vector lanes (CPUs), except under the cells tiling, whose traversal marches one; one with a
/// single lane (GPUs, where work-items already run in lock-step and registers are scarce).
int packets_per_item(const Scene& scene, int lanes);

/// The full program source, exactly as it is built (and dumped by --dump-kernel). Throws
/// std::invalid_argument for native math with double precision (OpenCL has no double native_*),
/// and for value slots in an eval_points program or outside the scene's literals.
std::string generate_kernel_source(const Scene& scene, const KernelOptions& options);

/// What the scene's map() skips behind bounding spheres: render.subtree_bounds, without groups by
/// place under render.literals: buffer (a program for every scene of the tree's shape).
SubtreeGates subtree_gates(const Scene& scene);

/// The scene's code in its march programs, literals open: the distance functions (points relative
/// to map_frame_origin, subtrees gated as render.subtree_bounds says) and the tiling's cell; with_ids,
/// map_color numbers the primitive it hit. Each literal has the same index with and without the ids.
SdfCode march_scene_code(const Scene& scene, bool with_ids = false);

/// What tells programs apart: their feature switches (the #defines), the shape of the scene's code
/// (code_shape of march_scene_code's source: literals open, comments out) and the bits of the
/// literals it spells (those outside
/// the value slots). Two scenes with equal keys under the same options run on one program; what
/// else differs between them (MarchParams: the camera, march limits and shading numbers; the
/// lights; the slots' values) reaches the device as data.
struct ProgramKey {
  std::string features;
  std::string code_shape;
  std::vector<std::uint32_t> spelled_literals;

  bool operator==(const ProgramKey&) const = default;
};
ProgramKey program_key(const Scene& scene, const KernelOptions& options);

/// The scene's code as a program built with options has it (eval_points: world points, every
/// literal spelled; march programs: march_scene_code, with ids where the purpose writes them).
SdfCode program_scene_code(const Scene& scene, const KernelOptions& options);

/// What the values buffer of the scene's march program built with options holds.
ProgramValues scene_values(const Scene& scene, const KernelOptions& options);

/// The output floor's program (kernels/output_floor.cl): fill_planes, which only stores.
std::string output_floor_source();

/// The build options of a variant: kBuildOptions, plus -cl-fast-relaxed-math when asked. They key
/// the driver's program cache together with the source (PoCL hashes both).
std::string kernel_build_options(const KernelVariant& variant);

}  // namespace clmarch
