// Binary little-endian PLY: positions in float or double, normals, 8-bit sRGB colours.
#include "mesh/format_writers.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <string>

namespace clmarch {
namespace {

std::string ply_header(const TriangleMesh& mesh, MeshPrecision precision) {
  const char* coordinate = precision == MeshPrecision::Double ? "double" : "float";
  std::string header = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment written by clmarch\nelement vertex {}\n"
      "property {} x\nproperty {} y\nproperty {} z\n",
      mesh.positions.size(), coordinate, coordinate, coordinate);
  if (!mesh.normals.empty()) header += "property float nx\nproperty float ny\nproperty float nz\n";
  if (!mesh.colors.empty()) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  header +=
      fmt::format("element face {}\nproperty list uchar uint vertex_indices\nend_header\n", mesh.triangles.size());
  return header;
}

}  // namespace

void write_ply(ChunkedFile& file, const TriangleMesh& mesh, MeshPrecision precision) {
  const std::string header = ply_header(mesh, precision);
  file.append(header.data(), header.size());
  const bool in_double = precision == MeshPrecision::Double;
  const std::size_t vertex_bytes = 3 * (in_double ? sizeof(double) : sizeof(float)) +
                                   (mesh.normals.empty() ? 0 : 3 * sizeof(float)) + (mesh.colors.empty() ? 0 : 3);
  append_records(file, mesh.positions.size(), vertex_bytes, [&](std::size_t i, char* at) {
    for (int axis = 0; axis < 3; ++axis) {
      const double coordinate = mesh.positions[i][axis];
      if (in_double) {
        pack(at, coordinate);
      } else {
        pack(at, static_cast<float>(coordinate));
      }
    }
    if (!mesh.normals.empty()) {
      for (int axis = 0; axis < 3; ++axis) pack(at, mesh.normals[i][axis]);
    }
    if (!mesh.colors.empty()) {
      for (int channel = 0; channel < 3; ++channel) pack(at, srgb_byte(mesh.colors[i][channel]));
    }
  });
  append_records(file, mesh.triangles.size(), 1 + 3 * sizeof(std::uint32_t), [&](std::size_t t, char* at) {
    pack(at, std::uint8_t{3});
    for (const std::uint32_t index : mesh.triangles[t]) pack(at, index);
  });
}

}  // namespace clmarch
