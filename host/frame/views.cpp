// Debug views from the buffers.
#include "frame/views.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace clmarch {
namespace {

void set_gray(FrameBuffers& b, std::size_t i, float v) {
  b.plane(Channel::R)[i] = v;
  b.plane(Channel::G)[i] = v;
  b.plane(Channel::B)[i] = v;
}

}  // namespace

std::array<float, 3> status_color(RayStatus status) {
  switch (status) {
    case RayStatus::Miss:
      return {0.0f, 0.0f, 0.0f};
    case RayStatus::Hit:
      return {0.5f, 0.5f, 0.5f};
    case RayStatus::OutOfSteps:
      return {1.0f, 0.0f, 1.0f};
    case RayStatus::OutOfDistance:
      return {0.0f, 0.0f, 0.5f};
  }
  return {0.0f, 0.0f, 0.0f};
}

void apply_view(FrameBuffers& buffers, View view, const RenderSettings& settings) {
  const std::size_t pixels = buffers.plane(Channel::Depth).size();
  const auto& depth = buffers.plane(Channel::Depth);
  switch (view) {
    case View::Shaded:
      return;
    case View::Normals:
      for (std::size_t i = 0; i < pixels; ++i) {
        const bool hit = std::isfinite(depth[i]);
        buffers.plane(Channel::R)[i] = hit ? buffers.plane(Channel::NX)[i] * 0.5f + 0.5f : 0.0f;
        buffers.plane(Channel::G)[i] = hit ? buffers.plane(Channel::NY)[i] * 0.5f + 0.5f : 0.0f;
        buffers.plane(Channel::B)[i] = hit ? buffers.plane(Channel::NZ)[i] * 0.5f + 0.5f : 0.0f;
      }
      return;
    case View::Depth: {
      float nearest = std::numeric_limits<float>::infinity();
      float farthest = 0.0f;
      for (float d : depth) {
        if (!std::isfinite(d)) continue;
        nearest = std::min(nearest, d);
        farthest = std::max(farthest, d);
      }
      const float range = std::max(farthest - nearest, 1e-30f);
      for (std::size_t i = 0; i < pixels; ++i) {
        set_gray(buffers, i, std::isfinite(depth[i]) ? 1.0f - 0.8f * (depth[i] - nearest) / range : 0.0f);
      }
      return;
    }
    case View::Steps:
      for (std::size_t i = 0; i < pixels; ++i) {
        set_gray(buffers, i, buffers.plane(Channel::Steps)[i] / static_cast<float>(settings.max_steps));
      }
      return;
    case View::Samples:
      for (std::size_t i = 0; i < pixels; ++i) {
        set_gray(buffers, i, buffers.plane(Channel::Samples)[i] / static_cast<float>(settings.samples));
      }
      return;
    case View::Status:
      for (std::size_t i = 0; i < pixels; ++i) {
        const std::array<float, 3> color = status_color(static_cast<RayStatus>(buffers.plane(Channel::Status)[i]));
        buffers.plane(Channel::R)[i] = color[0];
        buffers.plane(Channel::G)[i] = color[1];
        buffers.plane(Channel::B)[i] = color[2];
      }
      return;
  }
}

}  // namespace clmarch
