// Binary STL: float corners and facet normals, 50 bytes a triangle. The positions are kept as they
// come (a triangle repeats its corners); the triangles are written as they come.
#include "common/errors.hpp"
#include "mesh/format_writers.hpp"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace clmarch {
namespace {

/// The unit normal of the triangle a, b, c (counter-clockwise), or 0 for a degenerate one.
glm::dvec3 facet_normal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double length = glm::length(n);
  return length > 0.0 ? n / length : glm::dvec3(0.0);
}

void pack_vec3(char*& at, const glm::dvec3& v) {
  for (int axis = 0; axis < 3; ++axis) pack(at, static_cast<float>(v[axis]));
}

class StlWriter final : public MeshFileWriter {
 public:
  using MeshFileWriter::MeshFileWriter;

  std::uint64_t kept_bytes_per_vertex() const override { return sizeof(glm::dvec3); }
  std::uint64_t kept_bytes_per_triangle() const override { return 0; }

 private:
  void write_begin() override {
    // Readers take a header that starts with "solid" for ASCII STL.
    std::string header = "binary STL written by clmarch";
    header.resize(80, ' ');
    file().append(header.data(), header.size());
    if (layout().triangles > std::numeric_limits<std::uint32_t>::max()) {
      throw OutputError(fmt::format("{}: cannot write: {} triangles are more than binary STL's 32-bit count holds",
                                    file().target().string(), layout().triangles));
    }
    const auto count = static_cast<std::uint32_t>(layout().triangles);
    file().append(&count, sizeof count);
    positions_.reserve(layout().vertices);
  }

  void write_vertices(const VertexBlock& block) override {
    positions_.insert(positions_.end(), block.positions.begin(), block.positions.end());
  }

  void write_triangles(std::span<const MeshTriangle> block) override {
    append_records(file(), block.size(), 12 * sizeof(float) + sizeof(std::uint16_t), [&](std::size_t t, char* at) {
      const glm::dvec3& a = positions_[block[t][0]];
      const glm::dvec3& b = positions_[block[t][1]];
      const glm::dvec3& c = positions_[block[t][2]];
      pack_vec3(at, facet_normal(a, b, c));
      for (const glm::dvec3* corner : {&a, &b, &c}) pack_vec3(at, *corner);
      pack(at, std::uint16_t{0});
    });
  }

  std::vector<glm::dvec3> positions_;
};

}  // namespace

std::unique_ptr<MeshFileWriter> stl_writer(ChunkedFile& file) { return std::make_unique<StlWriter>(file); }

}  // namespace clmarch
