// Per-pixel output of a render, as planes of float, with the channel names of the --buffers EXR
// (part of the contract: R, G, B, depth, steps, N.x, N.y, N.z).
#pragma once

#include "common/cancellation.hpp"
#include "device_types.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace clmarch {

/// Output channels; the order up to WallSteps is also the plane order of the OpenCL output buffer.
/// WallSteps (the part of steps spent stepping to cell walls under tiling) is not an EXR channel of
/// the contract. Id is the number of the primitive the centre ray hit (scene/scene.hpp,
/// primitive_count; kMissId on a miss), written with the normals. A (coverage: the share of the pixel's samples that
/// hit) and Samples (how many it got) are filled on the host (host/frame/antialias.hpp).
enum class Channel {
  R,
  G,
  B,
  Depth,
  Steps,
  NX,
  NY,
  NZ,
  WallSteps,
  Id,
  AoR,
  AoG,
  AoB,
  DiffuseR,
  DiffuseG,
  DiffuseB,
  SpecularR,
  SpecularG,
  SpecularB,
  DepthLo,
  Status,
  A,
  Samples
};
inline constexpr int kChannelCount = 23;
/// Channel names (the EXR's, but for wall_steps), indexed by Channel.
inline constexpr const char* kChannelNames[kChannelCount] = {
    "R",          "G",          "B",          "depth",    "steps",  "N.x",       "N.y",       "N.z",
    "wall_steps", "id",         "ao.R",       "ao.G",     "ao.B",   "diffuse.R", "diffuse.G", "diffuse.B",
    "specular.R", "specular.G", "specular.B", "depth.lo", "status", "A",         "samples"};
/// How a centre ray ended, the status channel's values (CLMARCH_RAY_* in kernels/device_types.h).
enum class RayStatus {
  Miss = CLMARCH_RAY_MISS,
  Hit = CLMARCH_RAY_HIT,
  OutOfSteps = CLMARCH_RAY_OUT_OF_STEPS,
  OutOfDistance = CLMARCH_RAY_OUT_OF_DISTANCE
};
inline constexpr const char* kRayStatusNames[] = {"miss", "hit", "out_of_steps", "out_of_distance"};

/// The shading's layers (ao, diffuse, specular; r, g, b each): the terms of a hit's lit color
/// (kernels/shading.cl, LightTerms), written by shaded renders with the normals, 0 elsewhere.
inline constexpr Channel kLayerChannels[] = {Channel::AoR,       Channel::AoG,       Channel::AoB,
                                             Channel::DiffuseR,  Channel::DiffuseG,  Channel::DiffuseB,
                                             Channel::SpecularR, Channel::SpecularG, Channel::SpecularB};

/// Row-major planes, pixel (i, j) at j * width + i, j = 0 the top row. Linear color, depth +inf on
/// a miss, steps = distance evaluations of the march, N = unit normal (0 on a miss).
struct FrameBuffers {
  int width = 0;
  int height = 0;
  /// Whether the render filled Id, and the layers (programs without them leave them 0).
  bool has_ids = false;
  bool has_layers = false;
  /// Whether the render filled DepthLo: depth + depth.lo in double is the depth of a double render
  /// (render.precision: double, the --buffers program and the reference).
  bool has_depth_lo = false;
  /// Whether the render filled Status (the reference always; OpenCL programs with WRITE_STATUS).
  bool has_status = false;
  std::array<std::vector<float>, kChannelCount> planes;

  FrameBuffers() = default;
  /// Throws Cancelled between planes once Ctrl-C was pressed: a large image's 21 planes take
  /// seconds to allocate (2 GB at 4096 x 6144).
  FrameBuffers(int w, int h) : width(w), height(h) {
    for (auto& plane : planes) {
      throw_if_cancelled();
      plane.assign(static_cast<std::size_t>(w) * h, 0.0f);
    }
  }
  std::vector<float>& plane(Channel c) { return planes[static_cast<int>(c)]; }
  const std::vector<float>& plane(Channel c) const { return planes[static_cast<int>(c)]; }
  float& at(Channel c, int i, int j) { return plane(c)[static_cast<std::size_t>(j) * width + i]; }
  float at(Channel c, int i, int j) const { return plane(c)[static_cast<std::size_t>(j) * width + i]; }
  /// The pixels whose centre ray ended so (the status channel).
  std::uint64_t rays_with_status(RayStatus status) const {
    const float value = static_cast<float>(status);
    const std::vector<float>& p = plane(Channel::Status);
    return static_cast<std::uint64_t>(std::count(p.begin(), p.end(), value));
  }
};

}  // namespace clmarch
