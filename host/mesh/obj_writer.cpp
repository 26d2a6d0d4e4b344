// Wavefront OBJ text: vertices with sRGB colours, normals, 1-based triangles.
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

}  // namespace

void write_obj(ChunkedFile& file, const TriangleMesh& mesh, MeshPrecision precision) {
  fmt::memory_buffer line;
  fmt::format_to(std::back_inserter(line), "# written by clmarch: {} vertices, {} triangles\n", mesh.positions.size(),
                 mesh.triangles.size());
  if (!mesh.colors.empty()) fmt::format_to(std::back_inserter(line), "# v x y z r g b: r g b sRGB-encoded in [0, 1]\n");
  append_line(file, line);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (precision == MeshPrecision::Double) {
      format_position<double>(line, mesh.positions[i]);
    } else {
      format_position<float>(line, mesh.positions[i]);
    }
    if (!mesh.colors.empty()) {
      const glm::vec3& c = mesh.colors[i];
      // Six digits: far finer than a display's 8 bits, and 1 stays "1" (not float's 0.99999994).
      fmt::format_to(std::back_inserter(line), " {:.6g} {:.6g} {:.6g}", linear_to_srgb(c.r), linear_to_srgb(c.g),
                     linear_to_srgb(c.b));
    }
    line.push_back('\n');
    append_line(file, line);
  }
  for (const glm::vec3& n : mesh.normals) {
    fmt::format_to(std::back_inserter(line), "vn {} {} {}\n", n.x, n.y, n.z);
    append_line(file, line);
  }
  // OBJ counts from 1; a normal has its vertex's index.
  for (const auto& t : mesh.triangles) {
    const std::uint64_t a = std::uint64_t{t[0]} + 1, b = std::uint64_t{t[1]} + 1, c = std::uint64_t{t[2]} + 1;
    if (mesh.normals.empty()) {
      fmt::format_to(std::back_inserter(line), "f {} {} {}\n", a, b, c);
    } else {
      fmt::format_to(std::back_inserter(line), "f {0}//{0} {1}//{1} {2}//{2}\n", a, b, c);
    }
    append_line(file, line);
  }
}

}  // namespace clmarch
