// Where a mesh goes as it is made: its counts first, then its vertices in their numbers' order,
// then its triangles, each a block at a time, so that a file can be written while the mesh is
// made, without the whole mesh in memory (mesh_scene; the file writers of mesh_writers.hpp).
#pragma once

#include "mesh/triangle_mesh.hpp"

#include <cstdint>
#include <span>

namespace clmarch {

/// What a mesh will hold: announced before its first vertex.
struct MeshLayout {
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  bool normals = false;
  bool colors = false;
};

/// Consecutive vertices; normals and colours empty where the layout has none, else one a position.
struct VertexBlock {
  std::span<const glm::dvec3> positions;
  std::span<const glm::vec3> normals;
  std::span<const glm::vec3> colors;
};

class MeshSink {
 public:
  virtual ~MeshSink() = default;
  /// Host bytes the sink keeps for each vertex and each triangle until finish(): what mesh_scene
  /// adds to its memory prediction.
  virtual std::uint64_t kept_bytes_per_vertex() const = 0;
  virtual std::uint64_t kept_bytes_per_triangle() const = 0;
  /// Called once, before anything else.
  virtual void begin(const MeshLayout& layout) = 0;
  /// The next vertices; all of them come before the first triangle.
  virtual void add_vertices(const VertexBlock& block) = 0;
  /// The next triangles, counter-clockwise seen from outside.
  virtual void add_triangles(std::span<const MeshTriangle> block) = 0;
  /// Called once, after the last triangle.
  virtual void finish() = 0;
};

/// A sink that keeps the whole mesh (clmarch.mesh in Python, the tests).
class MeshCollector final : public MeshSink {
 public:
  TriangleMesh mesh;

  std::uint64_t kept_bytes_per_vertex() const override;
  std::uint64_t kept_bytes_per_triangle() const override;
  void begin(const MeshLayout& layout) override;
  void add_vertices(const VertexBlock& block) override;
  void add_triangles(std::span<const MeshTriangle> block) override;
  void finish() override {}
};

/// Gives mesh to sink: its layout, then its vertices and its triangles as one block each.
void send_mesh(const TriangleMesh& mesh, MeshSink& sink);

}  // namespace clmarch
