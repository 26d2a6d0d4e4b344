// Readers of mesh files independent of host/mesh/'s writers, for the tests: Assimp for every
// format, and the few lines that read what Assimp's single-precision build cannot show (PLY's
// doubles, OBJ's decimals, glTF's node translation).
#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <filesystem>
#include <optional>
#include <vector>

namespace clmarch::testing {

/// A triangle corner as a reader gave it: its world position, normal and colour where the file had them.
struct ReadCorner {
  glm::dvec3 position{0.0};
  std::optional<glm::dvec3> normal;
  std::optional<glm::dvec3> color;
};

/// Every triangle of every mesh of the file in file order, corners in the file's order, positions
/// through their nodes' transforms.
struct ReadTriangles {
  std::vector<std::array<ReadCorner, 3>> triangles;
  /// How many distinct positions the corners have.
  std::size_t distinct_positions() const;
};

/// The file read by Assimp (single precision: positions within float's step); throws
/// std::runtime_error with Assimp's message when it cannot read the file.
ReadTriangles read_with_assimp(const std::filesystem::path& path);

/// The vertex positions of a binary little-endian PLY whose x, y and z properties are float or double,
/// read at full precision.
std::vector<glm::dvec3> read_ply_positions(const std::filesystem::path& path);

/// The positions of an OBJ file's `v` lines, each number read as a double.
std::vector<glm::dvec3> read_obj_positions(const std::filesystem::path& path);

/// A glTF binary's two chunks: the JSON and the binary buffer.
struct GlbChunks {
  nlohmann::json json;
  std::vector<unsigned char> bin;
  /// The floats of accessor's vec3 elements (float, no byteStride: as our writer lays them out).
  std::vector<glm::dvec3> vec3s(int accessor) const;
};

/// A .glb file's chunks; throws std::runtime_error unless it is a glTF 2.0 binary container whose
/// length fields agree with the file.
GlbChunks read_glb(const std::filesystem::path& path);

}  // namespace clmarch::testing
