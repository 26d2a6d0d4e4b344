// The GLSL corpus (tests/glsl_corpus/, issue 42): our own Shadertoy-style distance functions, each
// evaluated by clmarch on OpenCL in float and in double and on the CPU reference, against Mesa's
// llvmpipe (scripts/glsl-corpus-truth.sh writes its values), and rendered through the cross check.
// The files are enumerated, so a new corpus file is covered the day its truth is written.
#include "api/check.hpp"
#include "api/field.hpp"
#include "cl/devices.hpp"
#include "support/test_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace clmarch {
namespace {

using testing::source_path;

const std::filesystem::path kCorpus = source_path("tests/glsl_corpus");
// The times the truth holds, as its files name them; in float, as llvmpipe's iTime is a float
// uniform and the OpenCL program reads the time from its float literals even in double precision.
const std::vector<std::pair<double, std::string>> kTimes = {{0.0, "0"}, {1.7f, "1.7"}};

// One lane (the scalar translation, which GPUs run) in float and double, and packets of 16 in float
// at the last time: the packet translation where the file has one (glsl/opencl_packets.hpp), else
// the scalar one a lane at a time. PoCL compiles the scalar program in half the time of the 16-lane
// one (the test's cost is its compiles), so packets are checked once per file.
const SessionOptions kOneLane{std::nullopt, 1};
const SessionOptions kPackets{std::nullopt, 16};

constexpr double kFloatEpsilon = std::numeric_limits<float>::epsilon();
// Against llvmpipe, in float ulps of the point's scale (scale_of). Two float implementations round
// each of a map's hundred-odd operations their own way (llvmpipe's sin, cos, atan and exp are its
// own polynomials; FMA contraction differs), and a rounding inside is carried out by the field's
// slope (noise and twists steepen it to a few units). The largest difference over the corpus is
// 14.8 ulps of scale (ring_folds at t 1.7: its angles), the reference's own 14.3; 64 leaves room
// for a new file and is at most 2.5e-5 (scale <= 3.3 at these points), a thousandth of the
// corpus's finest feature (a 0.02 rounding). MatchesLlvmpipe fails a tolerance that passes a
// thousandth of the values' range: it would check nothing.
constexpr double kFloatUlps = 64;
// The double program against the double interpreter: the same formulas, another libm, so double
// ulps of the scale (1024: the slope again); colours are then each rounded once to float
// (sample_field's colours are floats), which adds a float ulp of the value itself. Distances come
// back in double from both.
constexpr double kDoubleUlps = 1024;
constexpr double kDoubleEpsilon = std::numeric_limits<double>::epsilon();

std::vector<std::string> corpus_names() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kCorpus)) {
    if (entry.path().extension() == ".glsl") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Whether the file defines the colour function, by the rule the truth script uses.
bool has_albedo(const std::string& name) {
  std::istringstream lines(testing::read_text(kCorpus / (name + ".glsl")));
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("vec3 albedo(vec3 ", 0) == 0) return true;
  }
  return false;
}

struct TruthRow {
  glm::dvec3 p;
  double distance = 0.0;
  glm::dvec3 color;
};

// NAME.tTIME.csv: x,y,z,distance,r,g,b.
std::vector<TruthRow> read_truth(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line != "x,y,z,distance,r,g,b") {
    ADD_FAILURE() << path << ": missing or without its header; run scripts/glsl-corpus-truth.sh";
    return {};
  }
  std::vector<TruthRow> rows;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    double v[7];
    for (double& value : v) {
      std::string field;
      std::getline(fields, field, ',');
      value = std::stod(field);
    }
    rows.push_back({{v[0], v[1], v[2]}, v[3], {v[4], v[5], v[6]}});
  }
  return rows;
}

Scene corpus_scene(const std::string& name, const std::string& precision, double time) {
  const std::string color = has_albedo(name) ? ", color: albedo" : "";
  const std::string text = fmt::format(
      "camera: {{position: [0, 1.5, 5], look_at: [0, 0, 0], fov: 45}}\n"
      "render: {{width: 64, height: 36, precision: {}}}\n"
      "lights: [{{directional: {{direction: [1, 2, 1]}}}}]\n"
      "sdf: {{glsl: {{file: {}.glsl{}}}}}\n",
      precision, name, color);
  return load_scene_text(text, (kCorpus / (name + ".yaml")).string(), {}, time);
}

// A float computation's values at a point are rounded relative to the largest magnitudes in it:
// the coordinates, the result, and 1 (the shapes' sizes and the colours' range).
double scale_of(const TruthRow& row, double value) {
  return std::max({1.0, std::abs(row.p.x), std::abs(row.p.y), std::abs(row.p.z), std::abs(value)});
}

double float_tolerance(const TruthRow& row, double value) { return kFloatUlps * kFloatEpsilon * scale_of(row, value); }

// The double program's distance against the reference's, both doubles.
double double_tolerance(const TruthRow& row, double value) {
  return kDoubleUlps * kDoubleEpsilon * scale_of(row, value);
}

// The double program's colour against the reference's, both rounded to float at the end.
double double_color_tolerance(const TruthRow& row, double value) {
  return kFloatEpsilon * std::abs(value) + double_tolerance(row, value);
}

double range_of(const std::vector<double>& values) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return *high - *low;
}

// samples at the truth's points within float rounding of the truth's values.
void expect_near_truth(const std::string& where, const std::vector<TruthRow>& truth, const FieldSamples& samples,
                       bool color) {
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const TruthRow& row = truth[i];
    const std::string point = fmt::format("{}, point ({}, {}, {})", where, row.p.x, row.p.y, row.p.z);
    EXPECT_NEAR(samples.distance[i], row.distance, float_tolerance(row, row.distance)) << "distance of " << point;
    for (int c = 0; color && c < 3; ++c) {
      EXPECT_NEAR(samples.color[3 * i + c], row.color[c], float_tolerance(row, row.color[c]))
          << "colour channel " << c << " of " << point;
    }
  }
}

class GlslCorpus : public ::testing::TestWithParam<std::string> {};

// sample_field at the truth's points and times: OpenCL in float and in double and the reference
// within float rounding of llvmpipe, the double program within double rounding of the reference.
TEST_P(GlslCorpus, MatchesLlvmpipe) {
  const std::string& name = GetParam();
  const bool color = has_albedo(name);
  const bool fp64 = select_device(std::nullopt).has_fp64();
  for (const auto& [time, time_name] : kTimes) {
    const std::vector<TruthRow> truth = read_truth(kCorpus / fmt::format("{}.t{}.csv", name, time_name));
    ASSERT_FALSE(truth.empty()) << name << " at t " << time_name;
    std::vector<glm::dvec3> points;
    std::vector<double> distances;
    for (const TruthRow& row : truth) {
      points.push_back(row.p);
      distances.push_back(row.distance);
    }
    // The tolerance must leave the comparison something to check: far under the spread of the
    // distances, and of the colours' range [0, 1].
    double largest_tolerance = 0.0;
    for (const TruthRow& row : truth)
      largest_tolerance = std::max(largest_tolerance, float_tolerance(row, row.distance));
    EXPECT_LT(largest_tolerance, 1e-3 * range_of(distances)) << name << ": the distance's tolerance checks nothing";
    EXPECT_LT(largest_tolerance, 1e-3) << name << ": the colour's tolerance checks nothing";

    const std::string where = fmt::format("{} at t {}", name, time_name);
    const Scene scene = corpus_scene(name, "float", time);
    const FieldSamples reference = sample_field(scene, points, Backend::Reference);
    expect_near_truth(where + " on the reference", truth, reference, color);
    expect_near_truth(where + " on OpenCL in float", truth, sample_field(scene, points, Backend::OpenCl, kOneLane),
                      color);
    if (time_name == kTimes.back().second) {
      expect_near_truth(where + " on OpenCL in float, packets of 16", truth,
                        sample_field(scene, points, Backend::OpenCl, kPackets), color);
    }
    if (!fp64) continue;
    const FieldSamples opencl_double =
        sample_field(corpus_scene(name, "double", time), points, Backend::OpenCl, kOneLane);
    expect_near_truth(where + " on OpenCL in double", truth, opencl_double, color);
    for (std::size_t i = 0; i < truth.size(); ++i) {
      const double value = reference.distance[i];
      EXPECT_NEAR(opencl_double.distance[i], value, double_tolerance(truth[i], value))
          << "OpenCL double against the reference: distance of " << where << ", point " << i;
      for (int c = 0; color && c < 3; ++c) {
        const double value_c = reference.color[3 * i + c];
        EXPECT_NEAR(opencl_double.color[3 * i + c], value_c, double_color_tolerance(truth[i], value_c))
            << "OpenCL double against the reference: colour channel " << c << " of " << where << ", point " << i;
      }
    }
  }
}

// The scene renders on both backends, hits, has no NaN, and passes `clmarch check`.
TEST_P(GlslCorpus, RendersAndPassesTheCheck) {
  const std::string& name = GetParam();
  const Scene scene = corpus_scene(name, "float", kTimes.back().first);
  const CheckOutcome outcome = check_scene(scene, kOneLane);
  const CheckReport& report = outcome.report;
  EXPECT_TRUE(report.passed()) << name << "\n" << report.to_text();
  EXPECT_GT(report.both_hit, report.pixels / 50) << name << ": the shape should be in view";
  EXPECT_EQ(report.non_finite_opencl, 0) << name;
  EXPECT_EQ(report.non_finite_reference, 0) << name;
  if (report.out_of_steps_reference) {
    EXPECT_LE(*report.out_of_steps_reference, static_cast<std::uint64_t>(report.pixels / 100))
        << name << ": a field too steep for its steps";
  }
}

INSTANTIATE_TEST_SUITE_P(Files, GlslCorpus, ::testing::ValuesIn(corpus_names()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace clmarch
