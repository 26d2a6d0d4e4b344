// The camera contract (docs/scene-format.md): how pixel (i, j) becomes a ray. Both renderers and
// outside tools derive rays from exactly this; the OpenCL kernel applies the same formula to the
// basis computed here.
#pragma once

#include "scene/scene.hpp"

namespace clmarch {

/// Orthonormal camera frame, with the image-plane extents folded into right and up.
struct CameraBasis {
  glm::dvec3 origin{0.0};
  /// f = normalize(look_at - position)
  glm::dvec3 forward{0.0, 0.0, -1.0};
  /// r * aspect * tan(fov / 2), with r = normalize(cross(f, up))
  glm::dvec3 right_extent{1.0, 0.0, 0.0};
  /// u * tan(fov / 2), with u = cross(r, f)
  glm::dvec3 up_extent{0.0, 1.0, 0.0};
  int width = 1;
  int height = 1;
};

/// The frame of a camera for an image of width x height; the camera must be valid (loader-checked).
CameraBasis camera_basis(const Camera& camera, int width, int height);

/// Unit direction through the image point (x, y) in pixel units, x right, y down; the centre of
/// pixel (i, j) is (i + 0.5, j + 0.5).
glm::dvec3 camera_ray_direction(const CameraBasis& basis, double x, double y);

/// The world point the generated map() measures its points from (codegen folds it into the tree's
/// positions in double; the renderer passes the camera relative to it): the camera position rounded
/// to a multiple of kMapFrameGrid, so coordinates on the device stay small wherever the camera is,
/// while a camera that moves within a grid cell keeps the same program. 0 near the origin and for
/// tiled scenes (their cell traversal has its own camera-relative frame).
inline constexpr double kMapFrameGrid = 64.0;
glm::dvec3 map_frame_origin(const Scene& scene);

/// Unit direction through the centre of pixel (i, j).
glm::dvec3 pixel_ray_direction(const CameraBasis& basis, int i, int j);

}  // namespace clmarch
