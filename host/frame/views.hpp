// The debug views of the color image (shading.view), drawn on the host from the buffers so that
// both backends show them identically and the kernel needs no shading for them.
#pragma once

#include "frame/frame_buffers.hpp"
#include "scene/scene.hpp"

#include <array>

namespace clmarch {

/// Overwrites R, G, B with the view (normals: N * 0.5 + 0.5; depth: 1 at the nearest hit falling
/// to 0.2 at the farthest, 0 for misses; steps: steps / max_steps;
/// samples: the pixel's samples / render.samples; status: status_color). Shaded leaves them as they are.
void apply_view(FrameBuffers& buffers, View view, const RenderSettings& settings);

/// The status view's linear color of a ray's status: black for a miss, grey for a hit, magenta
/// for a ray out of steps, dark blue for one that reached max_distance (docs/scene-format.md).
std::array<float, 3> status_color(RayStatus status);

}  // namespace clmarch
