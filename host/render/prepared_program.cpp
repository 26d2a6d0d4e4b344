// Generating and building a scene's program.
#include "render/prepared_program.hpp"

#include "codegen/kernel_source.hpp"
#include "common/errors.hpp"

#include <fmt/format.h>

#include <numeric>

namespace clmarch {

KernelVariant scene_variant(const Scene& scene, KernelVariant variant) {
  if (scene.render.precision == Precision::Double) variant.precision = Precision::Double;
  return variant;
}

void check_precision_support(const Scene& scene, const KernelVariant& variant, const std::string& device,
                             bool has_fp64) {
  if (variant.precision != Precision::Double) return;
  const char* asked_by = scene.render.precision == Precision::Double ? "render.precision: double" : "precision=double";
  if (!has_fp64) {
    throw InputError(
        fmt::format("{}: {} needs a device with cl_khr_fp64 (double arithmetic), which {} lacks; choose another "
                    "device (clmarch devices) or render.precision: float",
                    scene.source_name, asked_by, device));
  }
}

bool literals_in_buffer(const Scene& scene, const KernelOptions& kernel_options, bool asked) {
  // auto spells them: spelled literals measured 0-16 % faster warm than read ones on the shipped
  // scenes (docs/performance.md, "Literals"), and only a session that edits numbers gains from a
  // program keyed by the tree's shape alone (it asks, RenderSession).
  if (kernel_options.purpose == KernelPurpose::EvalPoints) return false;
  const LiteralPlacement placement = scene.render.literals;
  if (placement == LiteralPlacement::Inline || (placement == LiteralPlacement::Auto && !asked)) return false;
  return !program_scene_code(scene, kernel_options).literals.empty();
}

PreparedProgram prepare_program(const Scene& scene, const OpenClOptions& options, KernelPurpose purpose) {
  const DeviceEntry device = select_device(options.device);
  const KernelVariant variant = scene_variant(scene, options.variant);
  check_precision_support(scene, variant, device.label(), device.has_fp64());
  KernelOptions kernel_options{purpose, options.lanes.value_or(default_lanes(device)), variant};
  kernel_options.ray_status = options.ray_status;
  kernel_options.fp_contraction = allows_fp_contraction(device);
  const bool march = purpose != KernelPurpose::EvalPoints;
  if (march) kernel_options.value_slots = options.value_slots;
  const bool in_buffer = literals_in_buffer(scene, kernel_options, options.literals_in_buffer);
  if (in_buffer) {
    kernel_options.value_slots.resize(program_scene_code(scene, kernel_options).literals.size());
    std::iota(kernel_options.value_slots.begin(), kernel_options.value_slots.end(), 0);
  }
  const std::string source = generate_kernel_source(scene, kernel_options);
  if (options.before_build) options.before_build(source);
  return {build_device_program(device, source, kernel_build_options(variant)),
          kernel_options.lanes,
          march ? packets_per_item(scene, kernel_options.lanes) : 1,
          march ? march_outputs(scene, purpose, options.ray_status).planes() : std::vector<int>{},
          source,
          kernel_options,
          program_key(scene, kernel_options),
          in_buffer,
          march && kernel_options.lanes > 1 && calls_stages(scene, program_scene_code(scene, kernel_options))};
}

}  // namespace clmarch
