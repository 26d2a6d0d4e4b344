// The coarse cone pass: its buffers, its kernel's arguments and its dispatch.
#include "render/cone_pass.hpp"

#include "render/device_inputs.hpp"
#include "scene/scene_bounds.hpp"

namespace clmarch {

std::optional<ConePass> make_cone_pass(const PreparedProgram& program, const Scene& scene,
                                       const std::optional<cl::Buffer>& values) {
  if (!uses_cone_pass(scene)) return std::nullopt;
  const DeviceProgram& dp = program.program;
  ConePass cones;
  cones.blocks =
      static_cast<std::size_t>(CLMARCH_COARSE_BLOCKS(scene.render.width)) * CLMARCH_COARSE_BLOCKS(scene.render.height);
  cones.dispatch = plan_point_dispatch(dp.device, cones.blocks, program.lanes);
  // The kernel stores whole vectors of lanes, padding included.
  const std::size_t bytes = cones.dispatch.plane_stride * sizeof(float);
  cones.starts = cl::Buffer(dp.context, CL_MEM_READ_WRITE, bytes);
  cones.steps = cl::Buffer(dp.context, CL_MEM_WRITE_ONLY | CL_MEM_HOST_READ_ONLY, bytes);
  cones.kernel = cl::Kernel(dp.program, "coarse_cones");
  cones.kernel.setArg(1, cones.starts);
  cones.kernel.setArg(2, cones.steps);
  set_scene_values_arg(cones.kernel, 3, values);
  return cones;
}

cl::Event enqueue_cone_pass(cl::CommandQueue& queue, ConePass& cones, const MarchParams& params) {
  cones.kernel.setArg(0, sizeof(MarchParams), &params);
  cl::Event event;
  queue.enqueueNDRangeKernel(cones.kernel, cl::NullRange, cl::NDRange(cones.dispatch.global_items),
                             cl::NDRange(cones.dispatch.local_items), nullptr, &event);
  return event;
}

std::vector<float> read_cone_plane(cl::CommandQueue& queue, const ConePass& cones, const cl::Buffer& plane) {
  std::vector<float> values(cones.blocks);
  queue.enqueueReadBuffer(plane, CL_TRUE, 0, values.size() * sizeof(float), values.data());
  return values;
}

}  // namespace clmarch
