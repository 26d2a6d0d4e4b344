// Hit positions from depths.
#include "frame/hit_positions.hpp"

#include "scene/camera_model.hpp"

#include <cmath>
#include <cstddef>

namespace clmarch {

std::array<std::vector<float>, 3> hit_positions(const FrameBuffers& buffers, const Camera& camera) {
  const CameraBasis basis = camera_basis(camera, buffers.width, buffers.height);
  const std::size_t pixels = static_cast<std::size_t>(buffers.width) * buffers.height;
  std::array<std::vector<float>, 3> position;
  for (std::vector<float>& axis : position) axis.assign(pixels, 0.0f);
  const std::vector<float>& depth = buffers.plane(Channel::Depth);
  for (int j = 0; j < buffers.height; ++j) {
    for (int i = 0; i < buffers.width; ++i) {
      const std::size_t at = static_cast<std::size_t>(j) * buffers.width + i;
      if (!std::isfinite(depth[at])) continue;
      const double t =
          static_cast<double>(depth[at]) + (buffers.has_depth_lo ? buffers.plane(Channel::DepthLo)[at] : 0.0);
      const glm::dvec3 p = basis.origin + t * pixel_ray_direction(basis, i, j);
      for (int axis = 0; axis < 3; ++axis) position[axis][at] = static_cast<float>(p[axis]);
    }
  }
  return position;
}

}  // namespace clmarch
