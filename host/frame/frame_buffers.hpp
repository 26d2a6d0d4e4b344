// Per-pixel output of a render, as planes of float, with the channel names of the --buffers EXR
// (part of the contract: R, G, B, depth, steps, N.x, N.y, N.z).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace clmarch {

/// Output channels; the order up to WallSteps is also the plane order of the OpenCL output buffer.
/// WallSteps (the part of steps spent stepping to cell walls under tiling) is not an EXR channel of
/// the contract. Id is the number of the primitive the centre ray hit (scene/scene.hpp,
/// primitive_count; kMissId on a miss), written with the normals. A (coverage: the share of the pixel's samples that hit) and Samples (how many it
/// got) are filled on the host (host/frame/antialias.hpp).
enum class Channel { R, G, B, Depth, Steps, NX, NY, NZ, WallSteps, Id, A, Samples };
inline constexpr int kChannelCount = 12;
/// Channel names (the EXR's, but for wall_steps), indexed by Channel.
inline constexpr const char* kChannelNames[kChannelCount] = {"R",   "G",   "B",   "depth",      "steps", "N.x",
                                                             "N.y", "N.z", "wall_steps", "id",    "A",
                                                             "samples"};

/// Row-major planes, pixel (i, j) at j * width + i, j = 0 the top row. Linear color, depth +inf on
/// a miss, steps = distance evaluations of the march, N = unit normal (0 on a miss).
struct FrameBuffers {
  int width = 0;
  int height = 0;
  std::array<std::vector<float>, kChannelCount> planes;

  FrameBuffers() = default;
  FrameBuffers(int w, int h) : width(w), height(h) {
    for (auto& plane : planes) plane.assign(static_cast<std::size_t>(w) * h, 0.0f);
  }
  std::vector<float>& plane(Channel c) { return planes[static_cast<int>(c)]; }
  const std::vector<float>& plane(Channel c) const { return planes[static_cast<int>(c)]; }
  float& at(Channel c, int i, int j) { return plane(c)[static_cast<std::size_t>(j) * width + i]; }
  float at(Channel c, int i, int j) const { return plane(c)[static_cast<std::size_t>(j) * width + i]; }
};

}  // namespace clmarch
