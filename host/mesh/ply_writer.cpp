// Binary little-endian PLY: positions in float or double, normals, 8-bit sRGB colours; the header
// from the announced counts, then each block as it comes.
#include "mesh/format_writers.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <string>

namespace clmarch {
namespace {

class PlyWriter final : public MeshFileWriter {
 public:
  PlyWriter(ChunkedFile& file, MeshPrecision precision)
      : MeshFileWriter(file), in_double_(precision == MeshPrecision::Double) {}

  std::uint64_t kept_bytes_per_vertex() const override { return 0; }
  std::uint64_t kept_bytes_per_triangle() const override { return 0; }

 private:
  void write_begin() override {
    const char* coordinate = in_double_ ? "double" : "float";
    std::string header = fmt::format(
        "ply\nformat binary_little_endian 1.0\ncomment written by clmarch\nelement vertex {}\n"
        "property {} x\nproperty {} y\nproperty {} z\n",
        layout().vertices, coordinate, coordinate, coordinate);
    if (layout().normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
    if (layout().colors) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    header += fmt::format("element face {}\nproperty list uchar uint vertex_indices\nend_header\n", layout().triangles);
    file().append(header.data(), header.size());
  }

  void write_vertices(const VertexBlock& block) override {
    const std::size_t vertex_bytes = 3 * (in_double_ ? sizeof(double) : sizeof(float)) +
                                     (layout().normals ? 3 * sizeof(float) : 0) + (layout().colors ? 3 : 0);
    append_records(file(), block.positions.size(), vertex_bytes, [&](std::size_t i, char* at) {
      for (int axis = 0; axis < 3; ++axis) {
        const double coordinate = block.positions[i][axis];
        if (in_double_) {
          pack(at, coordinate);
        } else {
          pack(at, static_cast<float>(coordinate));
        }
      }
      if (layout().normals) {
        for (int axis = 0; axis < 3; ++axis) pack(at, block.normals[i][axis]);
      }
      if (layout().colors) {
        for (int channel = 0; channel < 3; ++channel) pack(at, srgb_byte(block.colors[i][channel]));
      }
    });
  }

  void write_triangles(std::span<const MeshTriangle> block) override {
    append_records(file(), block.size(), 1 + 3 * sizeof(std::uint32_t), [&](std::size_t t, char* at) {
      pack(at, std::uint8_t{3});
      for (const std::uint32_t index : block[t]) pack(at, index);
    });
  }

  bool in_double_;
};

}  // namespace

std::unique_ptr<MeshFileWriter> ply_writer(ChunkedFile& file, MeshPrecision precision) {
  return std::make_unique<PlyWriter>(file, precision);
}

}  // namespace clmarch
