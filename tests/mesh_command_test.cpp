// `clmarch mesh`: the file a scene's surface becomes, its --stats line, and a one-line error with
// exit code 2 and no file for every bad input.
#include "common/errors.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <algorithm>
#include <fstream>

namespace clmarch {
namespace {

using testing::CommandResult;
using testing::run_clmarch;
using testing::source_path;

std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "clmarch-mesh-command";
  std::filesystem::create_directories(dir);
  std::filesystem::remove(dir / name);
  return dir / name;
}

TEST(MeshCommand, WritesTheSurfaceAndItsFigures) {
  const std::filesystem::path out = scratch("torus.stl");
  const CommandResult result = run_clmarch(
      {"mesh", source_path("scenes/torus.yaml").string(), "-o", out.string(), "--resolution", "32", "--stats"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json stats = nlohmann::json::parse(result.out);
  const auto triangles = stats.at("triangles").get<std::uint64_t>();
  EXPECT_GT(triangles, 1000u);
  // Binary STL: an 80-byte header, the count, 50 bytes a triangle.
  EXPECT_EQ(std::filesystem::file_size(out), 84 + 50 * triangles);
  EXPECT_EQ(stats.at("bytes").get<std::uint64_t>(), std::filesystem::file_size(out));
  EXPECT_EQ(stats.at("cells_sampled").get<std::uint64_t>() + stats.at("cells_pruned").get<std::uint64_t>(),
            stats.at("cells").get<std::uint64_t>());
  EXPECT_GT(stats.at("cells_pruned").get<std::uint64_t>(), 0u);
  // The surface's box: its longest side is --resolution cells.
  const auto box = stats.at("box").get<std::vector<std::vector<double>>>();
  double longest = 0.0;
  for (int axis = 0; axis < 3; ++axis) longest = std::max(longest, box.at(1).at(axis) - box.at(0).at(axis));
  EXPECT_NEAR(longest, 32 * stats.at("cell").get<double>(), 1e-9);
  EXPECT_EQ(stats.at("cell_method").get<std::string>(), "cubes");
  for (const char* key : {"setup_ms", "prune_ms", "sample_ms", "march_ms", "place_ms", "write_ms",
                          "peak_resident_bytes", "predicted_bytes", "vertices", "evaluations"}) {
    EXPECT_TRUE(stats.contains(key)) << key;
  }
  EXPECT_NE(result.err.find("wrote " + out.string()), std::string::npos) << result.err;
}

TEST(MeshCommand, PlyAndObjFilesKeepNoVerticesInMemoryWhileGltfKeepsTheMesh) {
  // The memory predicted before sampling counts what the file's writer keeps: nothing of the mesh
  // for PLY and OBJ (written as it is made), the positions for STL, the whole mesh and its binary
  // chunk for glTF (docs/performance.md measures the peaks).
  const auto predicted = [](const std::string& extension) {
    const CommandResult result = run_clmarch({"mesh", source_path("scenes/torus.yaml").string(), "-o",
                                              scratch("kept." + extension).string(), "--resolution", "32", "--stats"});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return nlohmann::json::parse(result.out).at("predicted_bytes").get<std::uint64_t>();
  };
  const std::uint64_t ply = predicted("ply"), obj = predicted("obj"), stl = predicted("stl"), glb = predicted("glb");
  EXPECT_EQ(ply, obj);
  EXPECT_LT(ply, stl);
  EXPECT_LT(stl, glb);
}

TEST(MeshCommand, TetrahedraGiveAboutThreeTimesTheTrianglesOfCubes) {
  const auto triangles = [](const std::string& cells) {
    const CommandResult result =
        run_clmarch({"mesh", source_path("scenes/torus.yaml").string(), "-o", scratch("cells.ply").string(),
                     "--resolution", "32", "--stats", "--cells", cells});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    const nlohmann::json stats = nlohmann::json::parse(result.out);
    EXPECT_EQ(stats.at("cell_method").get<std::string>(), cells);
    return static_cast<double>(stats.at("triangles").get<std::uint64_t>());
  };
  const double ratio = triangles("tetrahedra") / triangles("cubes");
  EXPECT_GT(ratio, 2.5);
  EXPECT_LT(ratio, 3.5);
}

TEST(MeshCommand, FractalsAreMeshedAtTheHitThresholdAndSaySo) {
  const std::filesystem::path out = scratch("bulb.ply");
  const CommandResult result =
      run_clmarch({"mesh", source_path("scenes/mandelbulb.yaml").string(), "-o", out.string(), "--resolution", "16"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.err.find("is an estimate, whose sign is no inside/outside test: meshed where it falls to "
                            "render.epsilon"),
            std::string::npos)
      << result.err;
}

TEST(MeshCommand, AMeshTooLargeForTheMachineIsRefusedBeforeSampling) {
  // At 4096 cells the unit sphere's surface crosses about 1.5e6 bricks: some 5 GiB of samples,
  // predicted from the bricks pruning kept, against the 2.5 GiB a 4 GB address space leaves (at
  // 2048 cells, 1.2 GiB since the PLY file is written as the mesh is made, it fits).
  const std::filesystem::path scene = scratch("big.yaml");
  std::ofstream(scene) << "sdf: {sphere: {radius: 1}}\n";
  const std::filesystem::path out = scratch("big.ply");
  const testing::CommandResult result = testing::run_clmarch_in_shell(
      "ulimit -v 4000000; ", {"mesh", scene.string(), "-o", out.string(), "--resolution", "4096"});
  EXPECT_EQ(result.exit_code, kExitBadInput) << result.err;
  EXPECT_NE(result.err.find("--resolution 4096: the mesh needs about"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("choose a lower resolution"), std::string::npos) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(MeshCommand, BadInputIsOneLineAndWritesNothing) {
  const std::filesystem::path out = scratch("bad.ply");
  const std::string torus = source_path("scenes/torus.yaml").string();
  const std::filesystem::path plane = scratch("plane.yaml");
  std::ofstream(plane) << "sdf: {plane: {normal: [0, 1, 0], offset: 0}}\n";
  // Bounded (by the first sphere's box), but the second sphere takes all of the first.
  const std::filesystem::path emptied = scratch("emptied.yaml");
  std::ofstream(emptied) << "sdf: {subtraction: [{sphere: {radius: 1}}, {sphere: {radius: 2}}]}\n";
  const struct {
    std::vector<std::string> args;
    std::string expected;
  } cases[] = {
      {{"mesh", torus, "-o", scratch("t.xyz").string()}, "cannot write meshes with extension '.xyz'"},
      {{"mesh", torus, "-o", out.string(), "--resolution", "4"}, "--resolution"},
      {{"mesh", torus, "-o", out.string(), "--precision", "half"}, "--precision"},
      {{"mesh", torus, "-o", out.string(), "--cells", "hexagons"}, "--cells"},
      {{"mesh", torus, "-o", out.string(), "--backend", "reference", "--device", "0"},
       "--device applies to the OpenCL backend"},
      {{"mesh", plane.string(), "-o", out.string()}, "the surface is unbounded"},
      {{"mesh", emptied.string(), "-o", out.string(), "--resolution", "16"},
       "emptied.yaml: the surface is nowhere inside its box at --resolution 16: no triangle to write"},
      {{"mesh", torus, "-o", "/no/such/folder/t.ply"}, "/no/such/folder"},
      {{"mesh", torus, "-o", out.string(), "--set", "sdf.torus.radius=1"}, "unknown key 'radius'"},
  };
  for (const auto& c : cases) {
    const CommandResult result = run_clmarch(c.args);
    EXPECT_EQ(result.exit_code, kExitBadInput) << c.expected << ": " << result.err;
    EXPECT_NE(result.err.find(c.expected), std::string::npos) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.expected;
  }
}

}  // namespace
}  // namespace clmarch
