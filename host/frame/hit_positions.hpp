// The world position of each pixel's centre-ray hit, from its depth and the camera: the P.x, P.y,
// P.z channels of the buffers EXR and the Python module's "P".
#pragma once

#include "frame/frame_buffers.hpp"
#include "scene/scene.hpp"

#include <array>
#include <vector>

namespace clmarch {

/// Planes x, y, z (row-major like the buffers): camera origin + depth along the pixel's ray, in
/// double when the render kept depth.lo; 0 on a miss.
std::array<std::vector<float>, 3> hit_positions(const FrameBuffers& buffers, const Camera& camera);

}  // namespace clmarch
