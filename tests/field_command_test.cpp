// `clmarch field` through the real executable: closed forms on both backends, the input's order,
// values that read back exactly (its bad inputs are in cli_errors_test.cpp).
#include "api/field.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <fstream>
#include <sstream>

namespace clmarch {
namespace {

using testing::CommandResult;
using testing::run_clmarch;
using testing::TempDir;

/// A row of the output: x, y, z, distance, r, g, b as written.
using Row = std::vector<std::string>;

std::vector<Row> read_rows(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y,z,distance,r,g,b");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    Row row;
    std::stringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(field);
    EXPECT_EQ(row.size(), 7u) << line;
    rows.push_back(row);
  }
  return rows;
}

template <typename T>
T parsed(const std::string& text) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  EXPECT_TRUE(error == std::errc() && end == text.data() + text.size()) << text;
  return value;
}

std::string csv_of(const std::vector<glm::dvec3>& points) {
  std::string text = "x,y,z\n";
  for (const glm::dvec3& p : points) text += fmt::format("{},{},{}\n", p.x, p.y, p.z);
  return text;
}

/// Runs `clmarch field` on scene and points in dir; the rows written.
std::vector<Row> field_rows(const TempDir& dir, const std::string& scene, const std::vector<glm::dvec3>& points,
                            const std::string& backend, const std::string& precision = "float") {
  std::ofstream(dir / "scene.yaml") << scene;
  std::ofstream(dir / "points.csv") << csv_of(points);
  const std::filesystem::path out = dir / (backend + ".csv");
  const CommandResult result =
      run_clmarch({"field", (dir / "scene.yaml").string(), "--points", (dir / "points.csv").string(), "-o",
                   out.string(), "--backend", backend, "--precision", precision});
  EXPECT_EQ(result.exit_code, 0) << result.err;
  return read_rows(out);
}

// A sphere's distance |p - c| - r is exact in float at these points (lengths 0.25, 1, 2, 5); the
// kernel's length() may be a few ulps off the rounded value.
constexpr double kFloatLength = 4e-7;

TEST(FieldCommand, BothBackendsGiveTheSpheresDistancesAndColoursInTheInputsOrder) {
  const std::string scene =
      "sdf:\n  union:\n"
      "    - sphere: {radius: 1, color: [1, 0.5, 0.25]}\n"
      "    - sphere: {center: [5, 0, 0], radius: 0.5, color: [0, 0, 1]}\n";
  struct Expected {
    glm::dvec3 p;
    double distance;
    glm::dvec3 color;
  };
  const glm::dvec3 first(1, 0.5, 0.25), second(0, 0, 1);
  // Not sorted by anything, so that a reordering shows.
  const std::vector<Expected> expected = {
      {{6, 0, 0}, 0.5, second},      {{0, 2, 0}, 1.0, first},   {{0, 0, 0}, -1.0, first}, {{-3, 0, 4}, 4.0, first},
      {{5, 0, 0.25}, -0.25, second}, {{5, -2, 0}, 1.5, second}, {{0, 0, -1}, 0.0, first},
  };
  std::vector<glm::dvec3> points;
  for (const Expected& e : expected) points.push_back(e.p);
  TempDir dir;
  for (const char* backend : {"opencl", "reference"}) {
    const std::vector<Row> rows = field_rows(dir, scene, points, backend);
    ASSERT_EQ(rows.size(), expected.size()) << backend;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Expected& e = expected[i];
      EXPECT_EQ(glm::dvec3(parsed<double>(rows[i][0]), parsed<double>(rows[i][1]), parsed<double>(rows[i][2])), e.p)
          << backend << " row " << i;
      EXPECT_NEAR(parsed<float>(rows[i][3]), e.distance, kFloatLength) << backend << " row " << i;
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(parsed<float>(rows[i][4 + c]), e.color[c]) << backend << " row " << i << " channel " << c;
    }
  }
}

TEST(FieldCommand, TheBackendsAgreeOnATorusAtScatteredPoints) {
  std::vector<glm::dvec3> points;
  for (int i = 0; i < 200; ++i) {
    // A fixed scatter over [-2, 2]^3 (golden-ratio sequences), the same on every run.
    const auto frac = [](double x) { return x - std::floor(x); };
    points.emplace_back(4 * frac(i * 0.618034) - 2, 4 * frac(i * 0.754878) - 2, 4 * frac(i * 0.569840) - 2);
  }
  TempDir dir;
  const std::string scene = testing::read_text(testing::source_path("scenes/torus.yaml"));
  const std::vector<Row> device = field_rows(dir, scene, points, "opencl");
  const std::vector<Row> reference = field_rows(dir, scene, points, "reference");
  ASSERT_EQ(device.size(), points.size());
  ASSERT_EQ(reference.size(), points.size());
  // Float against double evaluation of distances up to about 3: a few float ulps of it.
  constexpr double kFloatField = 2e-6;
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(parsed<float>(device[i][3]), parsed<float>(reference[i][3]), kFloatField) << "point " << i;
    for (int c = 4; c < 7; ++c) EXPECT_NEAR(parsed<float>(device[i][c]), parsed<float>(reference[i][c]), 1e-6);
  }
}

TEST(FieldCommand, EveryNumberReadsBackAsTheValueSampled) {
  const std::string scene = "sdf: {torus: {major_radius: 0.7, minor_radius: 0.3, color: [0.1, 0.7, 0.3]}}\n";
  const std::vector<glm::dvec3> points = {{0.1, 1.0 / 3.0, -0.2}, {1e-7, 2.0 / 3.0, 0.3}, {1.7, 0.1, 1e5}};
  TempDir dir;
  for (const Backend backend : {Backend::OpenCl, Backend::Reference}) {
    const std::string name = kBackendNames[static_cast<int>(backend)];
    const std::vector<Row> rows = field_rows(dir, scene, points, name);
    const FieldSamples samples = sample_field(testing::scene_from_yaml(scene), points, backend);
    ASSERT_EQ(rows.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(parsed<double>(rows[i][axis]), points[i][axis]) << name;
      // The reference's distances are doubles, the float program's floats.
      if (backend == Backend::Reference) {
        EXPECT_EQ(parsed<double>(rows[i][3]), samples.distance[i]) << name << " row " << i;
      } else {
        EXPECT_EQ(parsed<float>(rows[i][3]), samples.distance[i]) << name << " row " << i;
      }
      for (int c = 0; c < 3; ++c) EXPECT_EQ(parsed<float>(rows[i][4 + c]), samples.color[3 * i + c]) << name;
    }
  }
}

// --precision double keeps what float cannot hold, in the points and in the distances: 3e-9 off a
// unit sphere (float rounds 1 + 3e-9 to 1, and its answers to about 1e-7). Double's rounding of
// |p| - 1 near 1 is a few 1e-16.
TEST(FieldCommand, DoublePrecisionKeepsTheDigitsOfPointsAndDistances) {
  const std::string scene = "sdf: {sphere: {radius: 1}}\n";
  const double off = 3e-9;
  const std::vector<glm::dvec3> points = {{1 + off, 0, 0}, {0, -(1 + off), 0}, {0, 0, 1 - off}};
  const double expected[] = {off, off, -off};
  TempDir dir;
  for (const char* backend : {"opencl", "reference"}) {
    const std::vector<Row> rows = field_rows(dir, scene, points, backend, "double");
    ASSERT_EQ(rows.size(), points.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      EXPECT_NEAR(parsed<double>(rows[i][3]), expected[i], 1e-15) << backend << " row " << i;
  }
  // The same points in float lose the offset: the test tells the two apart.
  const std::vector<Row> rows = field_rows(dir, scene, points, "opencl", "float");
  ASSERT_EQ(rows.size(), points.size());
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_GT(std::abs(parsed<double>(rows[i][3]) - expected[i]), 1e-9);
}

}  // namespace
}  // namespace clmarch
