// glTF 2.0 binary through tinygltf: float positions offset from a node translation in double.
// tinygltf holds the whole binary chunk in memory, twice while it writes (its model's buffer and
// its copy for the file); the file itself goes out through ChunkedFile's buffer.
#include "common/errors.hpp"
#include "mesh/format_writers.hpp"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace clmarch {
namespace {

/// Room for the JSON chunk and the headers within GLB's uint32 total length; the JSON of one mesh
/// takes about 1 KB.
constexpr std::uint64_t kJsonAllowance = std::uint64_t{64} * 1024;

/// The byte layout of the one buffer: one bufferView per attribute and the indices.
struct BufferLayout {
  std::size_t positions = 0, normals = 0, colors = 0, indices = 0, size = 0;
};

BufferLayout buffer_layout(const TriangleMesh& mesh) {
  const std::size_t vec3_bytes = mesh.positions.size() * 3 * sizeof(float);
  BufferLayout layout;
  layout.normals = layout.positions + vec3_bytes;
  layout.colors = layout.normals + (mesh.normals.empty() ? 0 : vec3_bytes);
  layout.indices = layout.colors + (mesh.colors.empty() ? 0 : vec3_bytes);
  layout.size = layout.indices + mesh.triangles.size() * 3 * sizeof(std::uint32_t);
  return layout;
}

/// Appends a bufferView of buffer 0 and a float or unsigned-int accessor of it; returns the accessor's index.
int add_accessor(tinygltf::Model& model, std::size_t offset, std::size_t count, int type, int component_type,
                 int target) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = count * static_cast<std::size_t>(tinygltf::GetNumComponentsInType(type)) * 4;
  view.target = target;
  model.bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(model.bufferViews.size() - 1);
  accessor.componentType = component_type;
  accessor.count = count;
  accessor.type = type;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

/// Copies n vec3 values, each made float by convert, to data at offset.
template <typename Convert>
void fill_vec3(std::vector<unsigned char>& data, std::size_t offset, std::size_t n, Convert convert) {
  char* at = reinterpret_cast<char*>(data.data() + offset);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 v = convert(i);
    for (int axis = 0; axis < 3; ++axis) pack(at, v[axis]);
  }
}

/// The model of a mesh with triangles: buffer, views, accessors, mesh, material, node, scene.
tinygltf::Model mesh_model(const TriangleMesh& mesh) {
  glm::dvec3 low = mesh.positions.front(), high = low;
  for (const glm::dvec3& p : mesh.positions) {
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  const glm::dvec3 centre = 0.5 * (low + high);
  const BufferLayout layout = buffer_layout(mesh);
  const std::size_t n = mesh.positions.size();

  tinygltf::Model model;
  tinygltf::Buffer buffer;
  buffer.data.resize(layout.size);
  glm::vec3 local_low(std::numeric_limits<float>::max()), local_high(-std::numeric_limits<float>::max());
  fill_vec3(buffer.data, layout.positions, n, [&](std::size_t i) {
    const glm::vec3 local(mesh.positions[i] - centre);
    local_low = glm::min(local_low, local);
    local_high = glm::max(local_high, local);
    return local;
  });
  if (!mesh.normals.empty()) fill_vec3(buffer.data, layout.normals, n, [&](std::size_t i) { return mesh.normals[i]; });
  if (!mesh.colors.empty()) {
    fill_vec3(buffer.data, layout.colors, n,
              [&](std::size_t i) { return glm::clamp(mesh.colors[i], glm::vec3(0.0f), glm::vec3(1.0f)); });
  }
  char* at = reinterpret_cast<char*>(buffer.data.data() + layout.indices);
  for (const auto& triangle : mesh.triangles) {
    for (const std::uint32_t index : triangle) pack(at, index);
  }
  model.buffers.push_back(std::move(buffer));

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.material = 0;
  const int position = add_accessor(model, layout.positions, n, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                    TINYGLTF_TARGET_ARRAY_BUFFER);
  // glTF requires POSITION's bounds: those of the floats written, so that they hold exactly.
  model.accessors[position].minValues = {local_low.x, local_low.y, local_low.z};
  model.accessors[position].maxValues = {local_high.x, local_high.y, local_high.z};
  primitive.attributes["POSITION"] = position;
  if (!mesh.normals.empty()) {
    primitive.attributes["NORMAL"] = add_accessor(model, layout.normals, n, TINYGLTF_TYPE_VEC3,
                                                  TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  }
  if (!mesh.colors.empty()) {
    primitive.attributes["COLOR_0"] = add_accessor(model, layout.colors, n, TINYGLTF_TYPE_VEC3,
                                                   TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  }
  primitive.indices = add_accessor(model, layout.indices, mesh.triangles.size() * 3, TINYGLTF_TYPE_SCALAR,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.primitives.push_back(primitive);
  model.meshes.push_back(gltf_mesh);

  tinygltf::Material material;
  material.name = "clmarch";
  material.doubleSided = false;
  // glTF's default metallicFactor of 1 would show the surface as a metal.
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  model.materials.push_back(material);

  tinygltf::Node node;
  node.mesh = 0;
  node.translation = {centre.x, centre.y, centre.z};
  model.nodes.push_back(node);
  model.scenes.emplace_back().nodes = {0};
  return model;
}

/// Writes mesh as GLB to file.
void write_glb(ChunkedFile& file, const TriangleMesh& mesh) {
  const std::uint64_t bytes = buffer_layout(mesh).size;
  if (bytes + kJsonAllowance > std::numeric_limits<std::uint32_t>::max()) {
    throw OutputError(
        fmt::format("{}: cannot write: {} bytes of mesh data are more than glTF binary's 4 GiB (try .ply)",
                    file.target().string(), bytes));
  }
  tinygltf::Model model = mesh_model(mesh);
  model.defaultScene = 0;
  model.asset.version = "2.0";
  model.asset.generator = "clmarch";
  // tinygltf 2.7.0 ignores the stream's state and returns true whatever happened ("TODO: Check
  // error on stream.write"): a failed write only sets the stream's badbit, and file.close() reports it.
  std::ostream stream(&file);
  tinygltf::TinyGLTF().WriteGltfSceneToStream(&model, stream, false, true);
}

class GlbWriter final : public MeshFileWriter {
 public:
  using MeshFileWriter::MeshFileWriter;

  // The mesh, and at finish tinygltf's binary chunk twice (float positions, normals and colours,
  // and the indices).
  std::uint64_t kept_bytes_per_vertex() const override {
    return collector_.kept_bytes_per_vertex() + 2 * 3 * sizeof(glm::vec3);
  }
  std::uint64_t kept_bytes_per_triangle() const override { return 3 * sizeof(MeshTriangle); }

 private:
  void write_begin() override { collector_.begin(layout()); }
  void write_vertices(const VertexBlock& block) override { collector_.add_vertices(block); }
  void write_triangles(std::span<const MeshTriangle> block) override { collector_.add_triangles(block); }
  void write_finish() override { write_glb(file(), collector_.mesh); }

  MeshCollector collector_;
};

}  // namespace

std::unique_ptr<MeshFileWriter> glb_writer(ChunkedFile& file) { return std::make_unique<GlbWriter>(file); }

}  // namespace clmarch
