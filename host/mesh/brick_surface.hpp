// The bricks of a mesh grid that hold the surface, their samples, and what marching makes of them:
// vertices identified by their grid edge and numbered brick by brick, triangles by those numbers.
//
// A vertex belongs to the brick holding its edge's lower end (local coordinates 0 ... 7); a brick's
// cells also use the edges on its upper faces, which belong to its upper neighbours. Each brick's
// crossed edges are kept as a bit set with running counts, so that any brick finds a vertex's
// number in its owner's set in constant time, in parallel, without a map of edges: the numbering
// (bricks in z, y, x order, then the edges in the owner's order) is the same whatever bricks were
// pruned, so pruned and unpruned sampling give the identical mesh.
//
// Pruning may drop a brick the surface enters where the field's bound is not one (fractal
// estimates change faster than the distance): every brick with a face whose samples lie on both
// sides of the level has its neighbour across that face sampled too, until none is missing, so
// the mesh is closed wherever the surface stays inside the grid.
#pragma once

#include "mesh/cell_tables.hpp"
#include "mesh/mesh_field.hpp"
#include "mesh/mesh_grid.hpp"
#include "mesh/triangle_mesh.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace clmarch {

class BrickSurface {
 public:
  BrickSurface(const MeshGrid& grid, double level, CellMethod method);

  /// Samples the bricks not yet held, at most batch_points grid points a call of field, then the
  /// neighbours across every face the level crosses, until none is missing; on_batch(bricks) after
  /// each call. Returns the bricks added by the neighbours.
  std::uint64_t sample(MeshField& field, const std::vector<glm::ivec3>& bricks, std::size_t batch_points,
                       const std::function<void(std::size_t bricks)>& on_batch);

  /// Numbers the vertices of every brick (sorting the bricks in z, y, x order) and counts their
  /// triangles. Triangles that would use an edge outside the grid are left out (the surface reaches
  /// the grid's boundary: never for a scene's bounded surface, which has a cell of margin).
  void march();

  std::size_t bricks() const { return corners_.size(); }
  std::uint32_t vertices() const { return first_vertex_.empty() ? 0 : first_vertex_.back(); }
  /// The first vertex of brick b (in z, y, x order); vertices of b run up to first_vertex(b + 1).
  std::uint32_t first_vertex(std::size_t b) const { return first_vertex_[b]; }
  /// Appends the edges of brick b's vertices to seeds, in their numbers' order.
  void append_seeds(std::size_t b, std::vector<EdgeSeed>& seeds) const;

  std::uint64_t triangles() const { return first_triangle_.empty() ? 0 : first_triangle_.back(); }
  /// The first triangle of brick b; b's triangles run up to first_triangle(b + 1).
  std::uint64_t first_triangle(std::size_t b) const { return first_triangle_[b]; }
  /// Appends the triangles of bricks [first_brick, end_brick) to out, in the bricks' order: made
  /// again from the samples at each call, so that no more than a block of them is ever held. With
  /// cells, appends each triangle's cell_key there too (a cell's triangles are consecutive).
  void append_triangles(std::size_t first_brick, std::size_t end_brick, std::vector<MeshTriangle>& out,
                        std::vector<std::uint64_t>* cells = nullptr) const;
  std::uint64_t surface_cells() const { return surface_cells_; }
  std::uint64_t dropped_triangles() const { return dropped_triangles_; }

  /// Frees the samples (after the last append_seeds and append_triangles).
  void release_samples();

 private:
  /// Row (y, z) of a brick's samples as bits over x, set where the sample is below the level.
  using BelowRows = std::array<std::uint16_t, 81>;

  std::uint64_t key(const glm::ivec3& brick) const;
  BelowRows below_rows(const float* samples) const;
  /// Whether the samples of the brick's face on axis, side (0 low, 1 high) lie on both sides.
  bool face_crossed(const BelowRows& rows, int axis, int side) const;
  /// The number of edge slot `bit` of brick id's set: its first vertex plus the set bits before it.
  std::uint32_t vertex_number(std::uint32_t id, int bit) const;
  /// Writes brick id's triangles to out (and their cell_keys to cells, unless null), leaving out
  /// those with an edge past the grid; returns how many it wrote.
  std::uint64_t brick_triangles(std::size_t id, MeshTriangle* out, std::uint64_t* cells = nullptr) const;

  MeshGrid grid_;
  double level_;
  const CellTable& table_;
  const EdgeSteps& steps_;
  /// Words of a brick's edge set: 512 lower ends times the method's steps, in bits.
  int words_;
  /// Bit x of a byte moved to bit x * (the method's steps).
  std::array<std::uint64_t, 256> spread_{};

  // Bricks by slot (the order they were sampled in) and their samples.
  std::vector<glm::ivec3> corners_;
  std::vector<const float*> samples_;
  std::vector<std::unique_ptr<float[]>> blocks_;
  std::unordered_map<std::uint64_t, std::uint32_t> slot_of_;

  // Bricks by id (z, y, x order).
  std::vector<std::uint32_t> order_;
  /// Per id the ids of itself and its upper neighbours: offset (x, y, z) in {0, 1} at x + 2y + 4z,
  /// or -1 where it holds no samples.
  std::vector<std::array<std::int32_t, 8>> upper_;
  std::vector<std::uint64_t> edge_bits_;
  std::vector<std::uint16_t> bits_before_;
  std::vector<std::uint32_t> first_vertex_;
  std::vector<std::uint64_t> first_triangle_;
  std::uint64_t surface_cells_ = 0;
  std::uint64_t dropped_triangles_ = 0;
};

}  // namespace clmarch
