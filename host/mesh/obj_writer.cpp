// Wavefront OBJ text: vertices with sRGB colours, normals, 1-based triangles, each block written as
// it comes: a block's `v` lines, then its `vn` lines (OBJ numbers each kind of line on its own, so
// vertex i keeps normal i), then the `f` lines.
#include "image/image_writer.hpp"
#include "mesh/format_writers.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <iterator>

namespace clmarch {
namespace {

/// Appends the lines in line to file and empties it: one line at a time through the file's
/// buffer, never the whole text in memory.
void append_line(ChunkedFile& file, fmt::memory_buffer& line) {
  file.append(line.data(), line.size());
  line.clear();
}

/// "v x y z" with the shortest decimals that read back as the same T.
template <typename T>
void format_position(fmt::memory_buffer& line, const glm::dvec3& p) {
  fmt::format_to(std::back_inserter(line), "v {} {} {}", static_cast<T>(p.x), static_cast<T>(p.y), static_cast<T>(p.z));
}

class ObjWriter final : public MeshFileWriter {
 public:
  ObjWriter(ChunkedFile& file, MeshPrecision precision) : MeshFileWriter(file), precision_(precision) {}

  std::uint64_t kept_bytes_per_vertex() const override { return 0; }
  std::uint64_t kept_bytes_per_triangle() const override { return 0; }

 private:
  void write_begin() override {
    fmt::format_to(std::back_inserter(line_), "# written by clmarch: {} vertices, {} triangles\n", layout().vertices,
                   layout().triangles);
    if (layout().colors) {
      fmt::format_to(std::back_inserter(line_), "# v x y z r g b: r g b sRGB-encoded in [0, 1]\n");
    }
    append_line(file(), line_);
  }

  void write_vertices(const VertexBlock& block) override {
    for (std::size_t i = 0; i < block.positions.size(); ++i) {
      if (precision_ == MeshPrecision::Double) {
        format_position<double>(line_, block.positions[i]);
      } else {
        format_position<float>(line_, block.positions[i]);
      }
      if (layout().colors) {
        const glm::vec3& c = block.colors[i];
        // Six digits: far finer than a display's 8 bits, and 1 stays "1" (not float's 0.99999994).
        fmt::format_to(std::back_inserter(line_), " {:.6g} {:.6g} {:.6g}", linear_to_srgb(c.r), linear_to_srgb(c.g),
                       linear_to_srgb(c.b));
      }
      line_.push_back('\n');
      append_line(file(), line_);
    }
    for (const glm::vec3& n : block.normals) {
      fmt::format_to(std::back_inserter(line_), "vn {} {} {}\n", n.x, n.y, n.z);
      append_line(file(), line_);
    }
  }

  void write_triangles(std::span<const MeshTriangle> block) override {
    // OBJ counts from 1; a normal has its vertex's index.
    for (const MeshTriangle& t : block) {
      const std::uint64_t a = std::uint64_t{t[0]} + 1, b = std::uint64_t{t[1]} + 1, c = std::uint64_t{t[2]} + 1;
      if (layout().normals) {
        fmt::format_to(std::back_inserter(line_), "f {0}//{0} {1}//{1} {2}//{2}\n", a, b, c);
      } else {
        fmt::format_to(std::back_inserter(line_), "f {} {} {}\n", a, b, c);
      }
      append_line(file(), line_);
    }
  }

  MeshPrecision precision_;
  fmt::memory_buffer line_;
};

}  // namespace

std::unique_ptr<MeshFileWriter> obj_writer(ChunkedFile& file, MeshPrecision precision) {
  return std::make_unique<ObjWriter>(file, precision);
}

}  // namespace clmarch
