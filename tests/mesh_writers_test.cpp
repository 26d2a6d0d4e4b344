// The mesh writers read back by an independent reader (Assimp): every format keeps the triangles
// in order with their winding, and the normals and colours it has room for.
#include "common/errors.hpp"
#include "image/image_writer.hpp"
#include "mesh/format_writers.hpp"
#include "mesh/mesh_writers.hpp"
#include "support/mesh_checks.hpp"
#include "support/mesh_readers.hpp"
#include "support/test_meshes.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

namespace clmarch {
namespace {

using testing::Expected;
using testing::octahedron;
using testing::read_text;
using testing::read_with_assimp;
using testing::TempDir;
using testing::write_committed;

/// Coordinates below 2 in float, read back by Assimp (single precision): float's step there is
/// 2.4e-7, and Assimp's parsing of OBJ's decimals may add one more.
constexpr double kMeshFloatTolerance = 1e-6;
/// An 8-bit channel is within half a step of its value.
constexpr double kByteTolerance = 0.5 / 255.0 + 1e-6;

const glm::dvec3 kCentre{0.25, -0.5, 0.75};
constexpr double kRadius = 1.3;

std::vector<glm::dvec3> doubles(const std::vector<glm::vec3>& values) { return {values.begin(), values.end()}; }

/// The octahedron's positions and normals within float's step, and the colours given.
Expected octahedron_expected(const testing::KnownMesh& known, std::vector<glm::dvec3> colors, double color_tolerance) {
  return {.position_tolerance = kMeshFloatTolerance,
          .normals = doubles(known.mesh.normals),
          .normal_tolerance = kMeshFloatTolerance,
          .colors = std::move(colors),
          .color_tolerance = color_tolerance};
}

TEST(MeshWriters, ExtensionsInAnyCaseNameTheirFormats) {
  EXPECT_EQ(mesh_format_of("out.ply", "-o"), MeshFormat::Ply);
  EXPECT_EQ(mesh_format_of("a/b/out.STL", "-o"), MeshFormat::Stl);
  EXPECT_EQ(mesh_format_of("out.Obj", "-o"), MeshFormat::Obj);
  EXPECT_EQ(mesh_format_of("out.glb", "-o"), MeshFormat::Glb);
  for (std::size_t i = 0; i < std::size(kMeshFormatNames); ++i) {
    EXPECT_EQ(mesh_format_of(std::string("m.") + kMeshFormatNames[i], "-o"), static_cast<MeshFormat>(i));
  }
}

TEST(MeshWriters, OtherExtensionsAreRefusedNamingOptionAndPath) {
  for (const auto& [path, extension] : {std::pair{"dir/out.xyz", "'.xyz'"}, std::pair{"out", "''"},
                                        std::pair{"out.gltf", "'.gltf'"}, std::pair{"out.ply.png", "'.png'"}}) {
    try {
      mesh_format_of(path, "--output");
      ADD_FAILURE() << path << " accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), std::string("--output ") + path + ": cannot write meshes with extension " +
                                           extension + " (expected .ply, .stl, .obj or .glb)");
    }
  }
}

TEST(MeshWriters, PlyKeepsNormalsAndSrgbColoursInEitherPrecision) {
  TempDir dir;
  const testing::KnownMesh known = octahedron(kCentre, kRadius);
  for (const MeshPrecision precision : {MeshPrecision::Float, MeshPrecision::Double}) {
    write_committed(dir / "out.ply", known.mesh, MeshFormat::Ply, precision);
    const std::string text = read_text(dir / "out.ply");
    const char* coordinate = precision == MeshPrecision::Double ? "property double x\n" : "property float x\n";
    EXPECT_NE(text.find(coordinate), std::string::npos) << text.substr(0, 300);
    EXPECT_NE(text.find("element face 8\nproperty list uchar uint vertex_indices\nend_header\n"), std::string::npos);
    testing::expect_same_triangles(known.mesh, read_with_assimp(dir / "out.ply"),
                                   octahedron_expected(known, known.srgb_colors, kByteTolerance));
  }
}

TEST(MeshWriters, StlHasItsHeaderFiftyBytesATriangleAndFacetNormals) {
  TempDir dir;
  const TriangleMesh mesh = octahedron(kCentre, kRadius).mesh;
  write_committed(dir / "out.stl", mesh, MeshFormat::Stl);
  const std::string bytes = read_text(dir / "out.stl");
  ASSERT_EQ(bytes.size(), 80u + 4u + 50u * 8u);
  EXPECT_TRUE(bytes.starts_with("binary STL written by clmarch")) << bytes.substr(0, 80);
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, sizeof count);
  EXPECT_EQ(count, 8u);
  // The facet normal of an octahedron's face points from its centre through the face's centroid.
  std::vector<glm::dvec3> facet_normals;
  for (const auto& t : mesh.triangles) {
    facet_normals.push_back(
        glm::normalize(mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]] - 3.0 * kCentre));
  }
  const testing::ReadTriangles read = read_with_assimp(dir / "out.stl");
  testing::expect_same_triangles(mesh, read, {.position_tolerance = kMeshFloatTolerance});
  for (std::size_t t = 0; t < read.triangles.size(); ++t) {
    for (const testing::ReadCorner& corner : read.triangles[t]) {
      ASSERT_TRUE(corner.normal.has_value());
      EXPECT_LT(glm::length(*corner.normal - facet_normals[t]), kMeshFloatTolerance) << "triangle " << t;
      EXPECT_FALSE(corner.color.has_value()) << "STL has no colours";
    }
  }
}

TEST(MeshWriters, ObjKeepsNormalsAndSrgbColoursInEitherPrecision) {
  TempDir dir;
  const testing::KnownMesh known = octahedron(kCentre, kRadius);
  for (const MeshPrecision precision : {MeshPrecision::Float, MeshPrecision::Double}) {
    write_committed(dir / "out.obj", known.mesh, MeshFormat::Obj, precision);
    EXPECT_NE(read_text(dir / "out.obj").find("\nf 1//1 3//3 5//5\n"), std::string::npos) << "1-based, with normals";
    // OBJ's six digits of the sRGB values are within 5e-7 of them; the table's are exact.
    testing::expect_same_triangles(known.mesh, read_with_assimp(dir / "out.obj"),
                                   octahedron_expected(known, known.srgb_colors, kMeshFloatTolerance));
  }
}

TEST(MeshWriters, GlbKeepsNormalsAndLinearColoursAndItsNodeOffset) {
  TempDir dir;
  const testing::KnownMesh known = octahedron(kCentre, kRadius);
  write_committed(dir / "out.glb", known.mesh, MeshFormat::Glb);
  // Assimp applies the node's translation: world positions come back.
  testing::expect_same_triangles(known.mesh, read_with_assimp(dir / "out.glb"),
                                 octahedron_expected(known, doubles(known.mesh.colors), kMeshFloatTolerance));
  const testing::GlbChunks glb = testing::read_glb(dir / "out.glb");
  // The bounding box's centre, (low + high) / 2 in double, which may differ from kCentre in the last bit.
  const nlohmann::json& translation = glb.json.at("nodes").at(0).at("translation");
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(translation.at(axis).get<double>(), kCentre[axis], 1e-15);
  const nlohmann::json& primitive = glb.json.at("meshes").at(0).at("primitives").at(0);
  EXPECT_EQ(glb.json.at("accessors").at(primitive.at("indices").get<int>()).at("componentType"), 5125)
      << "UNSIGNED_INT indices";
  const nlohmann::json& material = glb.json.at("materials").at(primitive.at("material").get<int>());
  EXPECT_FALSE(material.value("doubleSided", false));
  EXPECT_EQ(material.at("pbrMetallicRoughness").at("metallicFactor"), 0.0);
  // glTF requires POSITION's min and max: those of the floats in the buffer, to the bit.
  const int position = primitive.at("attributes").at("POSITION").get<int>();
  const std::vector<glm::dvec3> local = glb.vec3s(position);
  for (int axis = 0; axis < 3; ++axis) {
    double low = local[0][axis], high = low;
    for (const glm::dvec3& p : local) low = std::min(low, p[axis]), high = std::max(high, p[axis]);
    EXPECT_EQ(glb.json.at("accessors").at(position).at("min").at(axis), low);
    EXPECT_EQ(glb.json.at("accessors").at(position).at("max").at(axis), high);
  }
}

TEST(MeshWriters, MeshesWithoutNormalsOrColoursLeaveThemOut) {
  TempDir dir;
  TriangleMesh mesh = octahedron(kCentre, kRadius).mesh;
  mesh.normals.clear();
  mesh.colors.clear();
  for (const MeshFormat format : {MeshFormat::Ply, MeshFormat::Obj, MeshFormat::Glb}) {
    const std::filesystem::path path = dir / (std::string("out.") + kMeshFormatNames[static_cast<int>(format)]);
    write_committed(path, mesh, format);
    const testing::ReadTriangles read = read_with_assimp(path);
    testing::expect_same_triangles(mesh, read, {.position_tolerance = kMeshFloatTolerance});
    for (const auto& triangle : read.triangles) {
      for (const testing::ReadCorner& corner : triangle) {
        EXPECT_FALSE(corner.normal.has_value()) << path;
        EXPECT_FALSE(corner.color.has_value()) << path;
      }
    }
  }
  EXPECT_EQ(read_text(dir / "out.ply").find("property float nx"), std::string::npos);
  EXPECT_EQ(read_text(dir / "out.ply").find("property uchar red"), std::string::npos);
  EXPECT_NE(read_text(dir / "out.obj").find("\nf 1 3 5\n"), std::string::npos);
}

// 40,000 vertices and 79,202 triangles: each file is larger than the 1 MiB chunk it is written in.
TEST(MeshWriters, SrgbBytesFromTheTableAreTheFormulas) {
  // Every 97th float of [0, 1], the codes' steps and their neighbours, and what lies outside.
  const auto direct = [](float x) { return static_cast<int>(std::lround(linear_to_srgb(x) * 255.0f)); };
  for (std::uint32_t bits = 0; bits <= std::bit_cast<std::uint32_t>(1.0f); bits += 97) {
    const float x = std::bit_cast<float>(bits);
    ASSERT_EQ(srgb_byte(x), direct(x)) << x;
  }
  for (int k = 0; k <= 255; ++k) {
    const float step = std::pow((k / 255.0f + 0.055f) / 1.055f, 2.4f);
    for (float x : {std::nextafter(step, 0.0f), step, std::nextafter(step, 2.0f)}) {
      if (x <= 1.0f) {
        ASSERT_EQ(srgb_byte(x), direct(x)) << x;
      }
    }
  }
  EXPECT_EQ(srgb_byte(-1.0f), 0);
  EXPECT_EQ(srgb_byte(2.0f), 255);
  EXPECT_EQ(srgb_byte(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(srgb_byte(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(MeshWriters, MeshesLargerThanAChunkReadBackWhole) {
  TempDir dir;
  const TriangleMesh mesh = testing::sheet(200);
  for (std::size_t i = 0; i < std::size(kMeshFormatNames); ++i) {
    const std::filesystem::path path = dir / (std::string("sheet.") + kMeshFormatNames[i]);
    write_committed(path, mesh, static_cast<MeshFormat>(i));
    EXPECT_GT(std::filesystem::file_size(path), 1u << 20) << path;
    testing::expect_same_triangles(mesh, read_with_assimp(path), {.position_tolerance = kMeshFloatTolerance});
  }
}

}  // namespace
}  // namespace clmarch
