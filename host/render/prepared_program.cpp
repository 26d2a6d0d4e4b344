// Generating and building a scene's program.
#include "render/prepared_program.hpp"

#include "codegen/kernel_source.hpp"

namespace clmarch {

PreparedProgram prepare_program(const Scene& scene, const OpenClOptions& options, KernelPurpose purpose) {
  const DeviceEntry device = select_device(options.device);
  KernelOptions kernel_options{purpose, options.lanes.value_or(default_lanes(device)), options.variant};
  kernel_options.fp_contraction = allows_fp_contraction(device);
  const bool march = purpose != KernelPurpose::EvalPoints;
  if (march) kernel_options.value_slots = options.value_slots;
  const std::string source = generate_kernel_source(scene, kernel_options);
  if (options.before_build) options.before_build(source);
  return {build_device_program(device, source, kernel_build_options(options.variant)), kernel_options.lanes,
          march ? packets_per_item(scene, kernel_options.lanes) : 1,
          march ? march_outputs(scene, purpose).planes() : std::vector<int>{}, source, kernel_options};
}

}  // namespace clmarch
