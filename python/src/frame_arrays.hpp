// A finished render held for Python: its planes handed out as NumPy arrays that view the render's
// own memory (never copied) and keep it alive, by the --buffers EXR's channel names.
#pragma once

#include "frame/frame_buffers.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace clmarch::python {

/// The render's planes, the hit positions and the composites (H x W x 3) built from them once.
struct FrameData {
  FrameBuffers buffers;
  RenderStats stats;
  std::array<std::vector<float>, 3> positions;
  std::vector<float> color;
  std::vector<float> normal;
  std::vector<float> position;
};

/// Takes the render's buffers over (no copy) and computes P and the composites.
std::shared_ptr<FrameData> hold_frame(RenderResult result, const Scene& scene);

/// Every channel as an array: the EXR's single channels (R, G, B, depth, steps, N.x, N.y, N.z, A,
/// samples, id, status, the layers, depth.lo when filled, P.x, P.y, P.z) as H x W float32, and
/// color, normal and P as H x W x 3. Each array's base owns a reference to frame.
pybind11::dict frame_channels(const std::shared_ptr<FrameData>& frame);

/// A C-ordered float32 array of the given shape over data (no copy), kept alive by owner.
pybind11::array_t<float> view_of(const std::vector<float>& data, const std::vector<pybind11::ssize_t>& shape,
                                 const std::shared_ptr<void>& owner);

}  // namespace clmarch::python
