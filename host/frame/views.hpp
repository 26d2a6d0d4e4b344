// The debug views of the color image (shading.view), drawn on the host from the buffers so that
// both backends show them identically and the kernel needs no shading for them.
#pragma once

#include "frame/frame_buffers.hpp"
#include "scene/scene.hpp"

namespace clmarch {

/// Overwrites R, G, B with the view (normals: N * 0.5 + 0.5; depth: 1 at the nearest hit falling
/// to 0.2 at the farthest, 0 for misses; steps: steps / max_steps;
/// samples: the pixel's samples / render.samples). Shaded leaves them as they are.
void apply_view(FrameBuffers& buffers, View view, const RenderSettings& settings);

}  // namespace clmarch
