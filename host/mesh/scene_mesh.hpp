// A scene's surface as a triangle mesh (`clmarch mesh`, clmarch.mesh): the bricks of a grid over
// the surface's box that the surface can cross (pruned with the field's bound), their samples,
// marching cubes (or tetrahedra) over them, then each vertex moved onto the real field and given
// its normal and colour.
#pragma once

#include "mesh/cell_tables.hpp"
#include "mesh/mesh_field.hpp"
#include "mesh/mesh_grid.hpp"
#include "mesh/mesh_sink.hpp"
#include "mesh/triangle_mesh.hpp"
#include "scene/scene.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace clmarch {

struct MeshSettings {
  /// Cells along the longest side of the surface's bounding box.
  int resolution = 256;
  CellMethod cells = CellMethod::Cubes;
  /// Whether bricks are pruned with the field's bound (false: every brick is sampled; the tests'
  /// check that pruning drops nothing).
  bool prune = true;
  /// Most field evaluations moving a vertex along its edge onto the level (most need 1-3).
  int refine_steps = 16;
  /// A vertex is on the level once the field there is within this share of a cell of it: far below
  /// what a mesh of that cell shows (the issue asks h / 20), above float rounding of coordinates.
  double tolerance_cells = 1e-4;
  /// Grid points sampled per call of the field; vertices placed per call are a quarter of it.
  std::size_t batch_points = std::size_t{1} << 20;
  /// Whether feature cells become fans around their tangent planes' meeting point (sharp_features.hpp):
  /// the whole mesh is then kept before the sink has it. Cubes only (tetrahedra put vertices inside
  /// cells, which a fan would leave unused).
  bool sharp = false;
  /// Triangles handed to the sink a block at a time: at least this many (a block ends with a brick),
  /// unless fewer are left.
  std::size_t triangles_per_block = std::size_t{1} << 20;
};

/// Figures of one mesh (`clmarch mesh --stats`).
struct MeshStats {
  glm::ivec3 grid_cells{0};
  double cell = 0.0;
  /// The box the surface lies in (surface_box), which the grid covers with a cell to spare.
  glm::dvec3 box_low{0.0};
  glm::dvec3 box_high{0.0};
  /// The level meshed: 0, or render.epsilon for fields that are estimates (fractals), whose sign
  /// is no inside/outside test; level_reason says why.
  double level = 0.0;
  std::string level_reason;
  std::string cell_method;
  std::uint64_t cells = 0;
  std::uint64_t cells_sampled = 0;
  std::uint64_t cells_pruned = 0;
  std::uint64_t bricks = 0;
  /// Bricks pruning dropped that the surface enters (sampled when a neighbour's face showed it).
  std::uint64_t bricks_restored = 0;
  std::uint64_t surface_cells = 0;
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  std::uint64_t evaluations = 0;
  /// The field's set-up (the device's program built or found in the driver's cache).
  double setup_ms = 0.0;
  double prune_ms = 0.0;
  double sample_ms = 0.0;
  double march_ms = 0.0;
  double place_ms = 0.0;
  /// Time in the sink (a file written as the mesh is made).
  double write_ms = 0.0;
  /// MeshSettings::sharp, and what it did: cells made fans, those whose planes met outside them (the
  /// fan's centre moved into the cell), edges flipped between fans, and its time.
  bool sharp = false;
  std::uint64_t feature_cells = 0;
  std::uint64_t feature_cells_clamped = 0;
  /// Feature cells left to marching's triangles, their fan folding (sharp_features.hpp).
  std::uint64_t feature_cells_folded = 0;
  std::uint64_t flipped_edges = 0;
  double sharp_ms = 0.0;
  /// Host memory predicted before sampling, and the process's peak resident memory after.
  std::uint64_t predicted_bytes = 0;
  std::uint64_t peak_resident_bytes = 0;

  nlohmann::json to_json() const;
};

struct SceneMesh {
  TriangleMesh mesh;
  MeshStats stats;
};

/// The box the surface lies in; throws InputError naming the scene when the tree is unbounded
/// (a plane, a tiling) or the box is empty.
void surface_box(const Scene& scene, double level, glm::dvec3& low, glm::dvec3& high);

/// Host bytes a mesh of active bricks needs at its peak, predicted before any brick is sampled:
/// the bricks' samples and records, the batches and blocks, and the bytes kept for each of the
/// surface's vertices and triangles (by the sink, and the whole mesh with sharp features) at their
/// measured share per brick (scene_mesh.cpp).
std::uint64_t predicted_mesh_bytes(std::uint64_t active_bricks, std::size_t batch_points,
                                   std::size_t triangles_per_block, CellMethod cells,
                                   std::uint64_t kept_bytes_per_vertex, std::uint64_t kept_bytes_per_triangle);

/// The field of a mesh whose grid starts at origin (opencl_field, reference_field).
using MeshFieldFor = std::function<std::unique_ptr<MeshField>(const glm::dvec3& origin)>;

/// Meshes scene on field_for(origin), the field evaluated at offsets from the grid's origin, into
/// sink as the mesh is made: vertices a batch of bricks at a time as they are placed, then
/// triangles a block of bricks at a time, made again from the samples. Throws InputError (naming
/// resolution_label) when the predicted memory exceeds what the machine has left.
MeshStats mesh_scene(const Scene& scene, const MeshSettings& settings, const MeshFieldFor& field_for,
                     const std::string& resolution_label, MeshSink& sink);

/// mesh_scene into a MeshCollector: the whole mesh in memory.
SceneMesh mesh_scene(const Scene& scene, const MeshSettings& settings, const MeshFieldFor& field_for,
                     const std::string& resolution_label);

}  // namespace clmarch
