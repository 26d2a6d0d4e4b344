// `clmarch check` as a function: the scene on OpenCL and on the CPU reference, compared pixel by
// pixel with tolerances derived from its settings (docs/accuracy.md).
#pragma once

#include "api/render_session.hpp"
#include "check/cross_check.hpp"
#include "frame/frame_buffers.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

namespace clmarch {

struct CheckOutcome {
  RenderResult opencl;
  FrameBuffers reference;
  CheckReport report;
};

/// Renders scene's buffers on both backends and compares them.
CheckOutcome check_scene(const Scene& scene, const SessionOptions& options = {});

}  // namespace clmarch
