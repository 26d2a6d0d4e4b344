// Meshes a million units from the origin, where float's step is 1/16: PLY and OBJ in double keep
// every position exactly, glTF keeps them through its node's translation, and every format still
// reads back through Assimp (single precision) within float's step.
#include "mesh/mesh_writers.hpp"
#include "support/mesh_checks.hpp"
#include "support/mesh_readers.hpp"
#include "support/test_meshes.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

namespace clmarch {
namespace {

using testing::TempDir;
using testing::write_committed;

// Thirds and sevenths are no multiples of float's step of 1/16 near 1e6, so a float is off by up to
// 1/32 at each corner, nor short decimals, which the shortest decimal of that float would restore.
const glm::dvec3 kFarCentre{1e6 + 1.0 / 3.0, -1e6 - 2.0 / 3.0, 1e6 + 1.0 / 7.0};
constexpr double kFarRadius = 1.3;
/// Float's step between 2^19 and 2^20: Assimp reads and transforms in single precision.
constexpr double kFloatStepAtAMillion = 1.0 / 16.0;
/// A float offset below 2 from the node's translation is within float's step there, 2.4e-7.
constexpr double kOffsetTolerance = 1e-6;

/// The largest coordinate difference between the two lists, which must have one length.
double largest_error(const std::vector<glm::dvec3>& read, const std::vector<glm::dvec3>& expected) {
  EXPECT_EQ(read.size(), expected.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < std::min(read.size(), expected.size()); ++i) {
    const glm::dvec3 d = glm::abs(read[i] - expected[i]);
    largest = std::max({largest, d.x, d.y, d.z});
  }
  return largest;
}

TEST(MeshWritersPrecision, DoublePlyAndObjKeepFarPositionsExactlyAndFloatOnesDoNot) {
  TempDir dir;
  const TriangleMesh mesh = testing::octahedron(kFarCentre, kFarRadius).mesh;
  for (const MeshFormat format : {MeshFormat::Ply, MeshFormat::Obj}) {
    const auto read = format == MeshFormat::Ply ? testing::read_ply_positions : testing::read_obj_positions;
    const std::filesystem::path path = dir / (std::string("far.") + kMeshFormatNames[static_cast<int>(format)]);
    write_committed(path, mesh, format, MeshPrecision::Double);
    EXPECT_EQ(largest_error(read(path), mesh.positions), 0.0) << path;
    // The same file in float is off by a visible fraction of float's step, so the check above can
    // fail: by half a step for the float, and in OBJ up to half a step more for its shortest decimal.
    write_committed(path, mesh, format, MeshPrecision::Float);
    const double float_error = largest_error(read(path), mesh.positions);
    EXPECT_GT(float_error, 0.01) << path;
    EXPECT_LE(float_error, kFloatStepAtAMillion) << path;
  }
}

TEST(MeshWritersPrecision, GlbKeepsFarPositionsAsFloatOffsetsFromItsNodeTranslation) {
  TempDir dir;
  const TriangleMesh mesh = testing::octahedron(kFarCentre, kFarRadius).mesh;
  write_committed(dir / "far.glb", mesh, MeshFormat::Glb);
  const testing::GlbChunks glb = testing::read_glb(dir / "far.glb");
  const nlohmann::json& node = glb.json.at("nodes").at(0);
  const glm::dvec3 translation(node.at("translation").at(0).get<double>(), node.at("translation").at(1).get<double>(),
                               node.at("translation").at(2).get<double>());
  // The bounding box's centre in double: within double's step at 1e6, 1.2e-10, of kFarCentre.
  EXPECT_LE(largest_error({translation}, {kFarCentre}), 2.5e-10);
  const int mesh_index = node.at("mesh").get<int>();
  const int position =
      glb.json.at("meshes").at(mesh_index).at("primitives").at(0).at("attributes").at("POSITION").get<int>();
  std::vector<glm::dvec3> world = glb.vec3s(position);
  for (glm::dvec3& p : world) p += translation;
  EXPECT_LE(largest_error(world, mesh.positions), kOffsetTolerance);
}

TEST(MeshWritersPrecision, EveryFormatReadsBackFarMeshesWithinFloatsStep) {
  TempDir dir;
  const TriangleMesh mesh = testing::octahedron(kFarCentre, kFarRadius).mesh;
  for (std::size_t i = 0; i < std::size(kMeshFormatNames); ++i) {
    const std::filesystem::path path = dir / (std::string("far.") + kMeshFormatNames[i]);
    write_committed(path, mesh, static_cast<MeshFormat>(i), MeshPrecision::Double);
    testing::expect_same_triangles(mesh, testing::read_with_assimp(path), {.position_tolerance = kFloatStepAtAMillion});
  }
}

}  // namespace
}  // namespace clmarch
