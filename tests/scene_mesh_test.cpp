// clmarch mesh's extraction: pruning keeps every brick the surface crosses, marching cubes give a
// closed, consistently oriented, welded mesh, and its vertices lie on the surface (closed forms of
// a sphere and a box on the reference; the device's field against the reference's).
#include "mesh/scene_mesh.hpp"

#include "common/errors.hpp"
#include "reference/reference_sdf.hpp"
#include "scene/scene_loader.hpp"
#include "render/prepared_program.hpp"
#include "support/mesh_topology.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>
#include <tuple>
#include <utility>

namespace clmarch {
namespace {

using testing::expect_watertight;

SceneMesh mesh_on_reference(const Scene& scene, int resolution) {
  MeshSettings settings;
  settings.resolution = resolution;
  return mesh_scene(
      scene, settings, [&](const glm::dvec3& origin) { return reference_field(scene, origin); }, "--resolution");
}

TEST(SceneMesh, ASphereIsClosedOutwardAndOnItsSurface) {
  const Scene scene =
      load_scene_text("sdf: {sphere: {center: [0.3, -0.2, 0.1], radius: 1, color: [0.2, 0.4, 0.6]}}\n", "sphere.yaml");
  const SceneMesh result = mesh_on_reference(scene, 32);
  const TriangleMesh& mesh = result.mesh;
  ASSERT_GT(mesh.triangles.size(), 1000u);
  expect_watertight(mesh.triangles);
  const glm::dvec3 centre(0.3, -0.2, 0.1);
  // The root finding stops once the field is within MeshSettings::tolerance_cells of a cell of 0
  // (the sphere's field is its distance), from a chord's sag of 1e-3 at 32 cells.
  const double on_surface = MeshSettings{}.tolerance_cells * result.stats.cell;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::dvec3 out = mesh.positions[v] - centre;
    ASSERT_NEAR(glm::length(out), 1.0, on_surface) << v;
    EXPECT_GT(glm::dot(glm::dvec3(mesh.normals[v]), glm::normalize(out)), 0.999) << v;
    EXPECT_NEAR(mesh.colors[v].z, 0.6f, 1e-6f);
  }
  // Counter-clockwise seen from outside: the triangles' normals point away from the centre.
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    ASSERT_GE(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0 - centre), 0.0);
  }
  const MeshStats& s = result.stats;
  EXPECT_GT(s.cells_pruned, 0u) << "the far corners of the box hold no surface";
  EXPECT_EQ(s.cells_sampled + s.cells_pruned, s.cells);
  EXPECT_EQ(s.level, 0.0);
}

TEST(SceneMesh, NoBrickTheSurfaceCrossesIsPruned) {
  const Scene scene = load_scene_text(
      "sdf:\n  union:\n    - torus: {major_radius: 1, minor_radius: 0.25}\n"
      "    - box: {center: [0, 0.9, 0], half_size: [0.3, 0.2, 0.5]}\n",
      "union.yaml");
  glm::dvec3 low, high;
  surface_box(scene, 0.0, low, high);
  const MeshGrid grid = mesh_grid(low, high, 48);
  const std::unique_ptr<MeshField> field = reference_field(scene, grid.origin);
  const ActiveBricks active = find_active_bricks(grid, *field, 0.0);
  std::set<std::tuple<int, int, int>> kept;
  for (const glm::ivec3& b : active.bricks) kept.insert({b.x, b.y, b.z});
  EXPECT_LT(active.bricks.size(), static_cast<std::size_t>(grid.bricks.x * grid.bricks.y * grid.bricks.z))
      << "something was pruned";
  // Every grid point's value, then every cell whose corners straddle 0 must be in a kept brick.
  const glm::ivec3 n = grid.cells + 1;
  std::vector<glm::dvec3> points;
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) points.push_back(glm::dvec3(x, y, z) * grid.cell);
  const std::vector<float> values = field->distances(points);
  const auto at = [&](int x, int y, int z) { return values[static_cast<std::size_t>((z * n.y + y) * n.x + x)]; };
  int crossing_cells = 0;
  for (int z = 0; z < grid.cells.z; ++z)
    for (int y = 0; y < grid.cells.y; ++y)
      for (int x = 0; x < grid.cells.x; ++x) {
        int below = 0;
        for (int c = 0; c < 8; ++c) below += at(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1)) < 0.0f;
        if (below == 0 || below == 8) continue;
        ++crossing_cells;
        ASSERT_TRUE(kept.count({x / kBrickCells, y / kBrickCells, z / kBrickCells}))
            << "cell " << x << " " << y << " " << z << " crosses the surface in a pruned brick";
      }
  EXPECT_GT(crossing_cells, 1000);
  // The mesh of those bricks is closed; its area is the torus's, 4 pi^2 R r = 9.87, less what the
  // box covers plus the box's faces outside the torus.
  const SceneMesh result = mesh_on_reference(scene, 48);
  expect_watertight(result.mesh.triangles);
  double area = 0.0;
  for (const auto& t : result.mesh.triangles) {
    const glm::dvec3 a = result.mesh.positions[t[0]], b = result.mesh.positions[t[1]], c = result.mesh.positions[t[2]];
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  EXPECT_GT(area, 9.0);
  EXPECT_LT(area, 9.87 + 2 * (0.6 * 0.4 + 0.6 * 1.0 + 0.4 * 1.0));
}

/// A sink that records the calls mesh_scene makes and keeps what they bring.
class RecordingSink final : public MeshSink {
 public:
  MeshCollector kept;
  MeshLayout layout;
  std::vector<std::string> calls;
  std::size_t largest_vertex_block = 0, largest_triangle_block = 0;

  std::uint64_t kept_bytes_per_vertex() const override { return 0; }
  std::uint64_t kept_bytes_per_triangle() const override { return 0; }
  void begin(const MeshLayout& l) override {
    calls.push_back("begin");
    layout = l;
    kept.begin(l);
  }
  void add_vertices(const VertexBlock& block) override {
    if (calls.back() != "vertices") calls.push_back("vertices");
    largest_vertex_block = std::max(largest_vertex_block, block.positions.size());
    kept.add_vertices(block);
  }
  void add_triangles(std::span<const MeshTriangle> block) override {
    if (calls.back() != "triangles") calls.push_back("triangles");
    largest_triangle_block = std::max(largest_triangle_block, block.size());
    kept.add_triangles(block);
  }
  void finish() override { calls.push_back("finish"); }
};

TEST(SceneMesh, TheMeshReachesTheSinkInBlocksAsItIsMade) {
  const Scene scene = load_scene_text("sdf: {torus: {major_radius: 1, minor_radius: 0.3}}\n", "torus.yaml");
  MeshSettings settings;
  settings.resolution = 48;
  const SceneMesh whole = mesh_scene(
      scene, settings, [&](const glm::dvec3& origin) { return reference_field(scene, origin); }, "--resolution");
  // Batches of 512 vertices and blocks of 1000 triangles at least: many of each.
  settings.batch_points = 2048;
  settings.triangles_per_block = 1000;
  RecordingSink sink;
  const MeshStats stats = mesh_scene(
      scene, settings, [&](const glm::dvec3& origin) { return reference_field(scene, origin); }, "--resolution", sink);
  EXPECT_EQ(sink.calls, (std::vector<std::string>{"begin", "vertices", "triangles", "finish"}));
  EXPECT_EQ(sink.layout.vertices, stats.vertices);
  EXPECT_EQ(sink.layout.triangles, stats.triangles);
  EXPECT_TRUE(sink.layout.normals && sink.layout.colors);
  ASSERT_GT(stats.triangles, 10'000u);
  // A batch of vertices ends with the brick that reached 512; a block of triangles likewise.
  EXPECT_LT(sink.largest_vertex_block, 512u + 8 * 8 * 8 * 3);
  EXPECT_GE(sink.largest_triangle_block, 1000u);
  EXPECT_LT(sink.largest_triangle_block, 1000u + 8 * 8 * 8 * 5);
  const TriangleMesh& blocks = sink.kept.mesh;
  EXPECT_EQ(blocks.positions, whole.mesh.positions);
  EXPECT_EQ(blocks.normals, whole.mesh.normals);
  EXPECT_EQ(blocks.triangles, whole.mesh.triangles) << "the triangles made again block by block are the same";
  expect_watertight(blocks.triangles);
}

TEST(SceneMesh, UnboundedScenesAreRefused) {
  const Scene plane = load_scene_text("sdf: {plane: {normal: [0, 1, 0], offset: 0}}\n", "plane.yaml");
  try {
    mesh_on_reference(plane, 16);
    FAIL() << "a plane has no bounded surface";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("plane.yaml: sdf: the surface is unbounded", 0), 0u) << e.what();
  }
}

TEST(SceneMesh, TheDeviceMeshIsTheReferences) {
  const Scene scene = load_scene_text("sdf: {box: {half_size: [0.5, 0.3, 0.4], rotate: [10, 20, 0]}}\n", "box.yaml");
  MeshSettings settings;
  settings.resolution = 24;
  const SceneMesh device = mesh_scene(
      scene, settings, [&](const glm::dvec3& origin) { return opencl_field(scene, OpenClOptions{}, origin); },
      "--resolution");
  const SceneMesh reference = mesh_on_reference(scene, 24);
  expect_watertight(device.mesh.triangles);
  // Float against double: the same cells cross the surface unless a corner's value is within
  // float rounding of 0, and the vertices agree to float rounding of the box's size.
  EXPECT_NEAR(static_cast<double>(device.mesh.triangles.size()), static_cast<double>(reference.mesh.triangles.size()),
              0.01 * reference.mesh.triangles.size());
  // Each device vertex lies on the box, also where the field kinks inside its corners: within the
  // root finding's tolerance of the device's level, which is the box's to a few float roundings of
  // the coordinates (at most 0.7 from the centre).
  const double tolerance =
      settings.tolerance_cells * device.stats.cell + 8 * std::numeric_limits<float>::epsilon() * 0.7;
  for (const glm::dvec3& p : device.mesh.positions) ASSERT_NEAR(reference_distance(scene.sdf, p), 0.0, tolerance);
}

TEST(SceneMesh, FarFromTheOriginADoubleFieldKeepsTheSurface) {
  Scene scene = load_scene_text("sdf: {sphere: {center: [1000000, 0, 0], radius: 1}}\n", "far.yaml");
  const glm::dvec3 centre(1e6, 0, 0);
  MeshSettings settings;
  settings.resolution = 16;
  const auto worst_offset = [&](const Scene& s) {
    const SceneMesh result = mesh_scene(
        s, settings, [&](const glm::dvec3& origin) { return opencl_field(s, OpenClOptions{}, origin); },
        "--resolution");
    double worst = 0.0;
    for (const glm::dvec3& p : result.mesh.positions) worst = std::max(worst, std::abs(glm::length(p - centre) - 1.0));
    return worst;
  };
  // In float the points 1e6 away are 1/16 apart: the vertices land anywhere within a few of them.
  EXPECT_GT(worst_offset(scene), 0.01);
  // In double the grid's offsets are added to its origin exactly: the root finding's tolerance
  // (cells of 0.17), plus float rounding of the offsets (under 1.5 from the origin).
  scene.render.precision = Precision::Double;
  EXPECT_LT(worst_offset(scene), settings.tolerance_cells * 0.17 + 8 * std::numeric_limits<float>::epsilon() * 1.5);
}

TEST(SceneMesh, TheMeshKernelsBuildCleanlyAndAgreeAtEveryPacketWidth) {
  const Scene scene = load_scene_text("sdf: {torus: {major_radius: 1, minor_radius: 0.3}}\n", "torus.yaml");
  MeshSettings settings;
  settings.resolution = 24;
  std::optional<SceneMesh> widest;
  for (int lanes : {16, 8, 4, 1}) {
    for (Precision precision : {Precision::Float, Precision::Double}) {
      Scene variant = scene;
      variant.render.precision = precision;
      OpenClOptions options;
      options.lanes = lanes;
      const PreparedProgram program = prepare_program(variant, options, KernelPurpose::EvalPoints);
      EXPECT_EQ(testing::compiler_warnings(program.program.build_log), "") << program.program.build_log;
      if (precision == Precision::Double) continue;
      const SceneMesh mesh = mesh_scene(
          variant, settings, [&](const glm::dvec3& origin) { return opencl_field(variant, options, origin); },
          "--resolution");
      expect_watertight(mesh.mesh.triangles);
      if (!widest) {
        widest = mesh;
        continue;
      }
      // The same cells and vertices: a packet's lanes compute what one lane does.
      EXPECT_TRUE(mesh.mesh.triangles == widest->mesh.triangles) << lanes << " lanes";
      ASSERT_EQ(mesh.mesh.positions.size(), widest->mesh.positions.size());
      for (std::size_t v = 0; v < mesh.mesh.positions.size(); ++v)
        ASSERT_LT(glm::length(mesh.mesh.positions[v] - widest->mesh.positions[v]), 1e-6) << lanes << " lanes";
    }
  }
}

}  // namespace
}  // namespace clmarch
