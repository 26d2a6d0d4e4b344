// Program assembly: defines first, then library files and generated code in dependency order.
#include "codegen/kernel_source.hpp"

#include "cl/device_program.hpp"
#include "common/errors.hpp"
#include "codegen/cl_literals.hpp"
#include "codegen/embedded_kernels.hpp"
#include "codegen/sdf_codegen.hpp"
#include "device_types.h"
#include "prune/operand_grid.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_bounds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <initializer_list>
#include <stdexcept>

namespace clmarch {
namespace {

/// The shadow modes' switch values, in ShadowMode's order.
constexpr const char* kShadowModeSwitches[] = {"CLMARCH_SHADOW_HARD", "CLMARCH_SHADOW_SOFT",
                                               "CLMARCH_SHADOW_SOFT_IMPROVED"};
static_assert(static_cast<int>(ShadowMode::Hard) == CLMARCH_SHADOW_HARD &&
                  static_cast<int>(ShadowMode::Soft) == CLMARCH_SHADOW_SOFT &&
                  static_cast<int>(ShadowMode::SoftImproved) == CLMARCH_SHADOW_SOFT_IMPROVED,
              "ShadowMode and the kernels' CLMARCH_SHADOW_* agree");

/// The switches of the shading's optional parts: which of MarchParams.shading's numbers the
/// program reads (kernels/shading.cl, atmosphere.cl).
std::string shading_defines(const Shading& s) {
  std::string out;
  if (s.model == ShadingModel::Phong) out += "#define SHADING_MODEL_PHONG\n";
  if (s.model == ShadingModel::BlinnPhong) out += "#define SHADING_MODEL_BLINN_PHONG\n";
  if (s.model == ShadingModel::Pbr) out += "#define SHADING_MODEL_PBR\n";
  if (s.shadows) out += fmt::format("#define SHADOW_MODE {}\n", kShadowModeSwitches[static_cast<int>(s.shadows->mode)]);
  if (s.ambient_occlusion) out += "#define AMBIENT_OCCLUSION\n";
  if (s.reflection_bounces > 0) out += "#define REFLECTIONS\n";
  if (s.step_ao > 0.0) out += "#define STEP_AO\n";
  if (s.fog) out += "#define FOG\n";
  if (s.sky) out += "#define SKY\n";
  if (s.glow) out += "#define GLOW\n";
  if (s.planetary_glow) out += "#define PLANET_GLOW\n";
  if (s.height_fog) out += "#define HEIGHT_FOG\n";
  if (s.tone_map == ToneMap::Reinhard) out += "#define TONE_MAP_REINHARD\n";
  if (s.gamma != 1.0) out += "#define DISPLAY_GAMMA\n";
  return out;
}

std::string feature_defines(const Scene& scene, const KernelOptions& options, const SdfCode& code) {
  std::string out = fmt::format("#define LANES {}\n", options.lanes);
  if (options.purpose == KernelPurpose::Ceiling) out += "#define RECORD_SAMPLES\n";
  if (options.purpose != KernelPurpose::EvalPoints) {
    out += fmt::format("#define PACKETS_PER_ITEM {}\n", packets_per_item(scene, options.lanes));
  }
  if (uses_antialiasing(scene, options.purpose)) out += "#define ANTIALIAS\n";
  if (options.variant.precision == Precision::Double) out += "#define DOUBLE_PRECISION\n";
  if (options.variant.native_math) out += "#define NATIVE_MATH\n";
  if (!options.fp_contraction) out += "#define NO_FP_CONTRACT\n";
  const MarchOutputs outputs = march_outputs(scene, options.purpose, options.ray_status);
  // Shading needs the normal whether or not its planes are written.
  if (outputs.normals) out += "#define WRITE_NORMALS\n";
  if (outputs.ids) out += "#define WRITE_IDS\n";
  if (outputs.layers) out += "#define WRITE_LAYERS\n";
  if (outputs.depth_lo) out += "#define WRITE_DEPTH_LO\n";
  if (outputs.status) out += "#define WRITE_STATUS\n";
  if (outputs.normals || outputs.color) {
    out += "#define NEED_NORMALS\n";
    if (scene.render.normal_method == NormalMethod::Tetrahedral) out += "#define NORMAL_TETRAHEDRAL\n";
    if (scene.render.normal_method == NormalMethod::Forward) out += "#define NORMAL_FORWARD\n";
  }
  if (outputs.color) {
    out += "#define NEED_SHADING\n" + shading_defines(scene.shading);
    if (std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& light) { return light.shaped(); })) {
      out += "#define SHAPED_LIGHTS\n";
    }
    if (uses_emission(scene.sdf)) out += "#define EMISSION\n";
  }
  if (uses_cone_pass(scene) && options.purpose != KernelPurpose::EvalPoints) out += "#define COARSE_PASS\n";
  if (options.purpose != KernelPurpose::EvalPoints && calls_stages(scene, code)) out += "#define STAGES_CALLED\n";
  if (scene.tiling && options.purpose != KernelPurpose::EvalPoints) {
    out += scene.tiling->method == TilingMethod::Cells ? "#define TILING_CELLS\n" : "#define TILING_MOD\n";
  }
  return out;
}

/// How the scene's map_color returns its materials.
MaterialLayout material_layout(const Scene& scene) {
  return {root_material(scene), scene.shading.model, uses_emission(scene.sdf)};
}

/// True if node or a descendant is of one of kinds: the library files of rare primitives are
/// compiled in only for the scenes that use them.
bool uses_kind(const Node& node, std::initializer_list<NodeKind> kinds) {
  if (std::find(kinds.begin(), kinds.end(), node.kind) != kinds.end()) return true;
  return std::any_of(node.children.begin(), node.children.end(),
                     [&](const Node& child) { return uses_kind(child, kinds); });
}

/// True if node or a descendant is of a kind of the group: profiles (kernels/profiles.cl), blend
/// operators (kernels/blend_operators.cl).
bool uses_group(const Node& node, bool (*in_group)(NodeKind)) {
  return in_group(node.kind) || std::any_of(node.children.begin(), node.children.end(),
                                            [&](const Node& child) { return uses_group(child, in_group); });
}

}  // namespace

SubtreeGates subtree_gates(const Scene& scene) {
  if (scene.render.subtree_bounds == SceneBounds::None) return SubtreeGates::None;
  // render.literals: buffer promises a program keyed by the tree's shape alone, whatever its
  // numbers, so the code must not follow where children are. Elsewhere a moved child may regroup
  // the union: another program (an animation's frames, a session's edits), never a wrong one.
  if (scene.render.literals == LiteralPlacement::Buffer) return SubtreeGates::Subtrees;
  return SubtreeGates::SubtreesAndPlaces;
}

/// The scene's code as eval_points has it: world points, every literal spelled.
SdfCode eval_points_scene_code(const Scene& scene) {
  return generate_sdf_code(scene.sdf, glm::dvec3(0.0), subtree_gates(scene), grid_union(scene), true,
                           material_layout(scene));
}

SdfCode program_scene_code(const Scene& scene, const KernelOptions& options) {
  if (options.purpose == KernelPurpose::EvalPoints) return eval_points_scene_code(scene);
  const MarchOutputs outputs = march_outputs(scene, options.purpose, options.ray_status);
  return march_scene_code(scene, outputs.ids);
}

bool uses_antialiasing(const Scene& scene, KernelPurpose purpose) {
  return scene.render.samples > 1 && purpose != KernelPurpose::EvalPoints && purpose != KernelPurpose::Ceiling;
}

std::string kernel_file(std::string_view name) {
  for (const EmbeddedFile& file : embedded_kernel_files()) {
    if (file.name == name) return fmt::format("#line 1 \"kernels/{}\"\n{}\n", name, file.contents);
  }
  throw std::logic_error(fmt::format("kernel file {} is not embedded", name));
}

std::vector<int> MarchOutputs::planes() const {
  std::vector<int> planes = {CLMARCH_CHANNEL_DEPTH, CLMARCH_CHANNEL_STEPS};
  if (status) planes.push_back(CLMARCH_CHANNEL_STATUS);
  if (color) planes.insert(planes.end(), {CLMARCH_CHANNEL_R, CLMARCH_CHANNEL_G, CLMARCH_CHANNEL_B});
  if (normals) planes.insert(planes.end(), {CLMARCH_CHANNEL_NX, CLMARCH_CHANNEL_NY, CLMARCH_CHANNEL_NZ});
  if (wall_steps) planes.push_back(CLMARCH_CHANNEL_WALL_STEPS);
  if (ids) planes.push_back(CLMARCH_CHANNEL_ID);
  if (depth_lo) planes.push_back(CLMARCH_CHANNEL_DEPTH_LO);
  if (layers) {
    for (int first : {CLMARCH_CHANNEL_AO, CLMARCH_CHANNEL_DIFFUSE, CLMARCH_CHANNEL_SPECULAR}) {
      planes.insert(planes.end(), {first, first + 1, first + 2});
    }
  }
  return planes;
}

MarchOutputs march_outputs(const Scene& scene, KernelPurpose purpose, bool ray_status) {
  MarchOutputs outputs;
  const bool buffers = purpose == KernelPurpose::Buffers;
  outputs.normals = purpose == KernelPurpose::Normals || purpose == KernelPurpose::Shaded || buffers;
  // A --buffers render's: the debug views' (Normals) and the shaded one's.
  outputs.ids = purpose == KernelPurpose::Normals || buffers;
  outputs.layers = buffers;
  outputs.depth_lo = buffers && scene.render.precision == Precision::Double;
  // Not in the timed programs (bench's Shaded and DepthSteps) unless asked: one more plane costs
  // the store-bound torus 5 % (1280x720 on PoCL).
  outputs.status = ray_status || buffers || purpose == KernelPurpose::Normals;
  outputs.color = purpose == KernelPurpose::Shaded || purpose == KernelPurpose::Color || buffers;
  outputs.wall_steps = uses_cells_tiling(scene);
  return outputs;
}

bool calls_stages(const Scene& scene, const SdfCode& code) {
  switch (scene.render.stages) {
    case KernelStages::Inline:
      return false;
    case KernelStages::Called:
      return true;
    case KernelStages::Auto:
      return code.source.size() >= kCalledStagesChars;
  }
  return false;
}

int packets_per_item(const Scene& scene, int lanes) { return lanes > 1 && !uses_cells_tiling(scene) ? 2 : 1; }

std::string generate_kernel_source(const Scene& scene, const KernelOptions& options) {
  if (options.variant.native_math && options.variant.precision == Precision::Double) {
    throw std::invalid_argument("native math needs float precision: OpenCL has no native_* functions for double");
  }
  std::string src = fmt::format("/* clmarch program for {} */\n", scene.source_name);
  const SdfCode code = program_scene_code(scene, options);
  src += feature_defines(scene, options, code);
  src += kernel_file("device_types.h");
  src += kernel_file("lanes.cl");
  src += kernel_file("primitives.cl");
  if (uses_kind(scene.sdf,
                {NodeKind::Mandelbulb, NodeKind::Menger, NodeKind::Sierpinski, NodeKind::Mandelbox, NodeKind::Julia})) {
    src += kernel_file("fractals.cl");
  }
  if (uses_group(scene.sdf, is_profile)) src += kernel_file("profiles.cl");
  if (uses_kind(scene.sdf, {NodeKind::Terrain})) src += kernel_file("noise.cl");
  src += kernel_file("operators.cl");
  if (uses_group(scene.sdf, is_blend_operator)) src += kernel_file("blend_operators.cl");
  if (uses_patterns(scene.sdf)) src += kernel_file("patterns.cl");
  src += "#line 1 \"generated scene\"\n";
  if (options.purpose == KernelPurpose::EvalPoints) {
    if (!options.value_slots.empty())
      throw std::invalid_argument("value slots are for march programs, not eval_points");
    // eval_points takes world points; the march's points are relative to map_frame_origin.
    src += spell_sdf_code(code);
    src += kernel_file("eval_points.cl");
    return src;
  }
  src += spell_sdf_code(code, options.value_slots);
  src += kernel_file("field.cl");
  src += kernel_file("camera.cl");
  src += kernel_file("march_loop.cl");
  if (uses_cells_tiling(scene)) src += kernel_file("tiling.cl");
  if (uses_cone_pass(scene)) src += kernel_file("coarse.cl");
  const MarchOutputs outputs = march_outputs(scene, options.purpose, options.ray_status);
  if (outputs.normals || outputs.color) src += kernel_file("normals.cl");
  if (outputs.color) {
    src += kernel_file("shading.cl");
    src += kernel_file("atmosphere.cl");
  }
  src += kernel_file("march.cl");
  if (options.purpose == KernelPurpose::Ceiling) src += kernel_file("replay.cl");
  return src;
}

namespace {

SdfCode scene_code(const Scene& scene, bool with_ids) {
  Literals literals;
  SdfCode code;
  code.source = sdf_functions(scene.sdf, map_frame_origin(scene), subtree_gates(scene), literals, grid_union(scene),
                              code.data, with_ids, material_layout(scene));
  code.literal_rounding = literals.distance_rounding();
  if (scene.tiling) {
    // The cell is the scene's geometry, like map()'s literals: an animation may vary it.
    code.source += fmt::format(
        "\n/* The tiling's cell (kernels/field.cl). */\nSDF_INLINE float4 tiling_cell(SceneValues values) {{ return "
        "{}; }}\n",
        literals.f4(scene.tiling->cell));
  }
  code.literals = literals.take();
  return code;
}

}  // namespace

SdfCode march_scene_code(const Scene& scene, bool with_ids) {
  // A number beyond float's range or an operand grid too large for memory is refused while the
  // code is generated, which knows nodes and not files.
  try {
    return scene_code(scene, with_ids);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", scene.source_name, e.what()));
  }
}

ProgramKey program_key(const Scene& scene, const KernelOptions& options) {
  SdfCode code = program_scene_code(scene, options);
  ProgramKey key{feature_defines(scene, options, code), code_shape(code.source), {}};
  const ValueSlots& slots = options.value_slots;
  for (std::size_t k = 0; k < code.literals.size(); ++k) {
    if (!std::binary_search(slots.begin(), slots.end(), static_cast<int>(k))) {
      key.spelled_literals.push_back(std::bit_cast<std::uint32_t>(code.literals[k]));
    }
  }
  return key;
}

ProgramValues scene_values(const Scene& scene, const KernelOptions& options) {
  return slot_values(program_scene_code(scene, options), options.value_slots);
}

std::string output_floor_source() { return kernel_file("output_floor.cl"); }

std::string kernel_build_options(const KernelVariant& variant) {
  std::string options = kBuildOptions;
  if (variant.fast_math) options += " -cl-fast-relaxed-math";
  return options;
}

}  // namespace clmarch
