// The camera contract in double precision.
#include "scene/camera_model.hpp"

#include <cmath>

namespace clmarch {

CameraBasis camera_basis(const Camera& camera, int width, int height) {
  const glm::dvec3 forward = glm::normalize(camera.look_at - camera.position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tan_half_fov = std::tan(glm::radians(camera.fov_degrees) * 0.5);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  CameraBasis basis;
  basis.origin = camera.position;
  basis.forward = forward;
  basis.right_extent = right * (aspect * tan_half_fov);
  basis.up_extent = up * tan_half_fov;
  basis.width = width;
  basis.height = height;
  return basis;
}

glm::dvec3 camera_ray_direction(const CameraBasis& basis, double x, double y) {
  const double sx = 2.0 * x / basis.width - 1.0;
  const double sy = 1.0 - 2.0 * y / basis.height;
  return glm::normalize(basis.forward + sx * basis.right_extent + sy * basis.up_extent);
}

glm::dvec3 pixel_ray_direction(const CameraBasis& basis, int i, int j) {
  return camera_ray_direction(basis, i + 0.5, j + 0.5);
}

glm::dvec3 map_frame_origin(const Scene& scene) {
  if (scene.tiling) return glm::dvec3(0.0);
  return glm::round(scene.camera.position / kMapFrameGrid) * kMapFrameGrid;
}

}  // namespace clmarch
