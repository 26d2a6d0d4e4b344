// The field a mesh is made from, behind one interface with two back ends: the scene's program on
// an OpenCL device (device_field.cpp) and the double-precision CPU reference (reference_field.cpp).
// Points are offsets from the mesh grid's origin, so that a double field keeps their precision far
// from the world's origin.
#pragma once

#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace clmarch {

/// A grid edge the level crosses, as marching found it: from grid point `point` to point + the
/// corner offset of `step` (bits x 1, y 2, z 4), with the field's samples at both ends.
struct EdgeSeed {
  glm::ivec3 point{0};
  int step = 1;
  float value_from = 0.0f;
  float value_to = 0.0f;
};

/// How vertices are moved onto the level: the root finding's stop and the normal's differences.
struct PlacementSettings {
  double level = 0.0;
  /// A vertex is placed once |field - level| is at most this.
  double tolerance = 0.0;
  /// Most field evaluations of the root finding per vertex.
  int max_steps = 8;
  /// The normal's taps are this far from the vertex along each axis (a tetrahedron's corners).
  double normal_step = 1e-4;
};

/// Where a vertex ended up on its edge (from + place * step offset), its unit normal, its colour
/// (linear albedo) and the field evaluations spent on it.
struct PlacedVertex {
  float place = 0.0f;
  glm::vec3 normal{0.0f};
  glm::vec3 color{0.0f};
  std::uint32_t evaluations = 0;
};

class MeshField {
 public:
  virtual ~MeshField() = default;

  /// The field's distance at each offset.
  virtual std::vector<float> distances(const std::vector<glm::dvec3>& offsets) = 0;

  /// The field at every grid point of each brick of `side` points along each axis from its corner
  /// (in cells), x fastest, then y, then z: brick b's values at out[b * side^3 ...].
  virtual void sample_bricks(std::span<const glm::ivec3> corners, int side, double cell, std::span<float> out) = 0;

  /// Each seed's vertex moved onto settings.level along its edge (grid points are at point * cell
  /// from the origin), with its normal and colour.
  virtual void place_vertices(std::span<const EdgeSeed> seeds, double cell, const PlacementSettings& settings,
                              std::span<PlacedVertex> out) = 0;
};

/// The scene's field on an OpenCL device (options.device), in the scene's precision; the program is
/// built once for every call.
std::unique_ptr<MeshField> opencl_field(const Scene& scene, const OpenClOptions& options, const glm::dvec3& origin);

/// The scene's field on the CPU reference, in double, on every core.
std::unique_ptr<MeshField> reference_field(const Scene& scene, const glm::dvec3& origin);

/// The corner offset (in cells) of a step's bits: x 1, y 2, z 4.
inline glm::ivec3 step_offset(int step) { return {step & 1, (step >> 1) & 1, (step >> 2) & 1}; }

}  // namespace clmarch
