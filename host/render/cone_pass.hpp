// The coarse cone pass (kernels/coarse.cl): one cone per block of pixels, marched before the
// camera rays, whose starts the march kernel reads.
#pragma once

#include "device_types.h"
#include "render/dispatch_plan.hpp"
#include "render/prepared_program.hpp"
#include "scene/scene.hpp"

#include <cstddef>
#include <optional>
#include <vector>

namespace clmarch {

/// The coarse cone pass of a program built with it (uses_cone_pass, kernels/coarse.cl): its kernel
/// and, per block of CLMARCH_COARSE_BLOCK^2 pixels, where the block's rays start and the cone's
/// steps. The march kernel reads the starts (bind_march_inputs).
struct ConePass {
  cl::Kernel kernel;
  Dispatch dispatch;
  std::size_t blocks = 0;
  cl::Buffer starts;
  cl::Buffer steps;
};
/// The cone pass of program for scene (reading values, make_scene_values), or nothing when the
/// scene has none.
std::optional<ConePass> make_cone_pass(const PreparedProgram& program, const Scene& scene,
                                       const std::optional<cl::Buffer>& values);
/// Enqueues the cone pass with params (before the march's chunks, which read its starts).
cl::Event enqueue_cone_pass(cl::CommandQueue& queue, ConePass& cones, const MarchParams& params);
/// One value per block of the cone pass's starts or steps (a blocking read).
std::vector<float> read_cone_plane(cl::CommandQueue& queue, const ConePass& cones, const cl::Buffer& plane);

}  // namespace clmarch
