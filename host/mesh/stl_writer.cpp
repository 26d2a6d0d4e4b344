// Binary STL: float corners and facet normals, 50 bytes a triangle.
#include "common/errors.hpp"
#include "mesh/format_writers.hpp"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <limits>
#include <string>

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

}  // namespace

void write_stl(ChunkedFile& file, const TriangleMesh& mesh) {
  // Readers take a header that starts with "solid" for ASCII STL.
  std::string header = "binary STL written by clmarch";
  header.resize(80, ' ');
  file.append(header.data(), header.size());
  if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw OutputError(fmt::format("{}: cannot write: {} triangles are more than binary STL's 32-bit count holds",
                                  file.target().string(), mesh.triangles.size()));
  }
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  file.append(&count, sizeof count);
  append_records(file, mesh.triangles.size(), 12 * sizeof(float) + sizeof(std::uint16_t), [&](std::size_t t, char* at) {
    const auto& triangle = mesh.triangles[t];
    const glm::dvec3& a = mesh.positions[triangle[0]];
    const glm::dvec3& b = mesh.positions[triangle[1]];
    const glm::dvec3& c = mesh.positions[triangle[2]];
    pack_vec3(at, facet_normal(a, b, c));
    for (const glm::dvec3* corner : {&a, &b, &c}) pack_vec3(at, *corner);
    pack(at, std::uint16_t{0});
  });
}

}  // namespace clmarch
