// The scene's field at given points, on either backend: the distance and the surface's colour
// there, and the primitive the colour is of (`clmarch.field` in Python, training data, probes).
#pragma once

#include "api/render_session.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <vector>

namespace clmarch {

/// One value per point, in the points' order.
struct FieldSamples {
  /// As the backend computed it: the reference's and a double program's doubles, a float program's
  /// floats.
  std::vector<double> distance;
  /// Whether distance holds doubles (the reference, a double program) rather than floats.
  bool distance_in_double = false;
  /// r, g, b per point (linear albedo of the material there).
  std::vector<float> color;
  /// The primitive's number (the id channel's numbering).
  std::vector<float> id;
};

/// The scene's SDF tree at the world points, repeated over the tiling's cell where the scene tiles
/// space. OpenCL evaluates the generated map() and map_color() in the program's precision, from
/// points rounded to it; the reference in double.
FieldSamples sample_field(const Scene& scene, const std::vector<glm::dvec3>& points, Backend backend,
                          const SessionOptions& options = {});

}  // namespace clmarch
