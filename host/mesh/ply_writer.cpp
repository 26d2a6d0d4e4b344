// Binary little-endian PLY: positions in float or double, normals, 8-bit sRGB colours.
#include "image/image_writer.hpp"
#include "mesh/format_writers.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace clmarch {
namespace {

/// The 8-bit sRGB code of a linear colour channel, as PLY viewers show colours.
std::uint8_t srgb_byte(float linear) { return static_cast<std::uint8_t>(std::lround(linear_to_srgb(linear) * 255.0f)); }

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
  // The largest vertex record: 3 doubles, 3 floats, 3 bytes.
  std::array<char, 3 * sizeof(double) + 3 * sizeof(float) + 3> record{};
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    char* at = record.data();
    for (int axis = 0; axis < 3; ++axis) {
      const double coordinate = mesh.positions[i][axis];
      if (precision == MeshPrecision::Double) {
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
    file.append(record.data(), static_cast<std::size_t>(at - record.data()));
  }
  std::array<char, 1 + 3 * sizeof(std::uint32_t)> face{};
  for (const auto& triangle : mesh.triangles) {
    char* at = face.data();
    pack(at, std::uint8_t{3});
    for (const std::uint32_t index : triangle) pack(at, index);
    file.append(face.data(), face.size());
  }
}

}  // namespace clmarch
