// Keeping a whole mesh, and sending one.
#include "mesh/mesh_sink.hpp"

namespace clmarch {

std::uint64_t MeshCollector::kept_bytes_per_vertex() const { return sizeof(glm::dvec3) + 2 * sizeof(glm::vec3); }

std::uint64_t MeshCollector::kept_bytes_per_triangle() const { return sizeof(MeshTriangle); }

void MeshCollector::begin(const MeshLayout& layout) {
  mesh = TriangleMesh{};
  mesh.positions.reserve(layout.vertices);
  if (layout.normals) mesh.normals.reserve(layout.vertices);
  if (layout.colors) mesh.colors.reserve(layout.vertices);
  mesh.triangles.reserve(layout.triangles);
}

void MeshCollector::add_vertices(const VertexBlock& block) {
  mesh.positions.insert(mesh.positions.end(), block.positions.begin(), block.positions.end());
  mesh.normals.insert(mesh.normals.end(), block.normals.begin(), block.normals.end());
  mesh.colors.insert(mesh.colors.end(), block.colors.begin(), block.colors.end());
}

void MeshCollector::add_triangles(std::span<const MeshTriangle> block) {
  mesh.triangles.insert(mesh.triangles.end(), block.begin(), block.end());
}

void send_mesh(const TriangleMesh& mesh, MeshSink& sink) {
  sink.begin({mesh.positions.size(), mesh.triangles.size(), !mesh.normals.empty(), !mesh.colors.empty()});
  sink.add_vertices({mesh.positions, mesh.normals, mesh.colors});
  sink.add_triangles(mesh.triangles);
  sink.finish();
}

}  // namespace clmarch
