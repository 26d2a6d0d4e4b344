// Anti-aliasing (render.samples, render.adaptive): the sample points, coverage of a disc and of a
// turned square against their exact area per pixel, the centre ray's channels left as they were,
// the reference against the kernel, and bad input.
#include "codegen/kernel_source.hpp"
#include "frame/antialias.hpp"
#include "reference/reference_renderer.hpp"
#include "render/host_memory.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/camera_model.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

namespace clmarch {
namespace {

using testing::error_of;
using testing::scene_from_yaml;

/// White solids on black under ambient light alone: a pixel's exact value is its covered area.
/// The camera looks down -z from z = 5 at a 32 x 32 image (fov 45).
std::string high_contrast_scene(const std::string& sdf, int samples, bool adaptive) {
  return "camera: {position: [0, 0, 5], look_at: [0, 0, 0], fov: 45}\n"
         "render: {width: 32, height: 32, samples: " +
         std::to_string(samples) + ", adaptive: " + (adaptive ? "true" : "false") +
         "}\n"
         "shading: {ambient: 1, background: 0}\n"
         "sdf: " +
         sdf + "\n";
}

/// Image-plane units per pixel of the 32 x 32, fov 45 camera: 2 tan(22.5 deg) / 32.
double plane_per_pixel() { return 2.0 * std::tan(glm::radians(22.5)) / 32.0; }

/// The exact share of pixel (i, j) inside the region of the image plane where inside(x, y) holds,
/// for a region whose every column is one interval [low(x), high(x)] in y: the integral over x of
/// the column's overlap with the pixel, by the midpoint rule on 4000 columns (error ~1e-7).
double exact_coverage(int i, int j, const std::function<std::pair<double, double>(double)>& column) {
  const int steps = 4000;
  double area = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double px = i + (k + 0.5) / steps;           // pixel units, from the left edge
    const double x = (px - 16.0) * plane_per_pixel();  // image plane, right
    const auto [low, high] = column(x);                // image plane, up
    // Pixel row j spans plane y from (16 - j - 1) to (16 - j) pixels.
    const double top = (16.0 - j) * plane_per_pixel(), bottom = (15.0 - j) * plane_per_pixel();
    area += std::max(0.0, std::min(high, top) - std::max(low, bottom)) / plane_per_pixel();
  }
  return area / steps;
}

/// A sphere of radius r at the origin seen from distance 5: a disc of radius tan(asin(r / 5)) on
/// the image plane at distance 1.
std::pair<double, double> disc_column(double x, double r) {
  const double radius = std::tan(std::asin(r / 5.0));
  if (std::abs(x) >= radius) return {0.0, 0.0};
  const double h = std::sqrt(radius * radius - x * x);
  return {-h, h};
}

/// A box with half size s turned by angle about the view axis, its front face at z = s: from z = 5
/// a square of half side s / (5 - s), turned likewise (its sides and back hide behind the face).
std::pair<double, double> square_column(double x, double s, double angle) {
  const double half = s / (5.0 - s);
  // The square |u| <= half, |v| <= half with u = x cos + y sin, v = -x sin + y cos: for this x the
  // y interval is the intersection of two slabs.
  const double c = std::cos(angle), sn = std::sin(angle);
  double low = -1e9, high = 1e9;
  const auto slab = [&](double a, double b) {  // |a + b y| <= half
    if (std::abs(b) < 1e-12) {
      if (std::abs(a) > half) high = low - 1.0;
      return;
    }
    const double y0 = (-half - a) / b, y1 = (half - a) / b;
    low = std::max(low, std::min(y0, y1));
    high = std::min(high, std::max(y0, y1));
  };
  slab(x * c, sn);
  slab(-x * sn, c);
  return high > low ? std::make_pair(low, high) : std::make_pair(0.0, 0.0);
}

std::vector<double> exact_image(const std::function<std::pair<double, double>(double)>& column) {
  std::vector<double> exact(32 * 32);
  for (int j = 0; j < 32; ++j) {
    for (int i = 0; i < 32; ++i) exact[j * 32 + i] = exact_coverage(i, j, column);
  }
  return exact;
}

double rms_error(const std::vector<float>& image, const std::vector<double>& exact) {
  double sum = 0.0;
  for (std::size_t i = 0; i < exact.size(); ++i) sum += (image[i] - exact[i]) * (image[i] - exact[i]);
  return std::sqrt(sum / exact.size());
}

/// The largest error of an N-sample estimate of a pixel cut by one straight edge: the points are a
/// (0, m, 2)-net in base 2 (N = 2^m), so each of the N square cells of side 1 / sqrt(N) (m even)
/// holds one point; the edge crosses at most 2 sqrt(N) - 1 of them, each off by at most 1 / N.
/// A curved edge inside one pixel is straight to well within that. Plus float rounding.
double edge_error_bound(int samples) { return (2.0 * std::sqrt(samples) - 1.0) / samples + 1e-5; }

TEST(Antialias, SamplePointsStartAtTheCentreAndAreStratified) {
  EXPECT_EQ(sample_point(0, 16), glm::dvec2(0.5, 0.5));
  EXPECT_EQ(sample_point(0, 1), glm::dvec2(0.5, 0.5));
  for (int count : {4, 16, 64, 256}) {
    std::set<int> columns, rows, cells;
    const int side = static_cast<int>(std::lround(std::sqrt(count)));
    for (int k = 0; k < count; ++k) {
      const glm::dvec2 p = sample_point(k, count);
      ASSERT_GE(p.x, 0.0);
      ASSERT_LT(p.x, 1.0);
      ASSERT_GE(p.y, 0.0);
      ASSERT_LT(p.y, 1.0);
      columns.insert(static_cast<int>(p.x * count));
      rows.insert(static_cast<int>(p.y * count));
      cells.insert(static_cast<int>(p.y * side) * side + static_cast<int>(p.x * side));
    }
    EXPECT_EQ(columns.size(), static_cast<std::size_t>(count)) << count;
    EXPECT_EQ(rows.size(), static_cast<std::size_t>(count)) << count;
    EXPECT_EQ(cells.size(), static_cast<std::size_t>(count)) << count;
  }
}

TEST(Antialias, AdaptiveDecisionFlagsBothSidesOfAnEdgeOnly) {
  FrameBuffers f(6, 3);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 6; ++i) {
      f.at(Channel::Depth, i, j) = i < 3 ? 2.0f : INFINITY;
      f.at(Channel::R, i, j) = f.at(Channel::G, i, j) = f.at(Channel::B, i, j) = i < 3 ? 0.5f : 0.0f;
    }
  }
  const std::vector<std::uint8_t> refine = pixels_to_refine(f, true);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 6; ++i) EXPECT_EQ(refine[j * 6 + i], i == 2 || i == 3 ? 1 : 0) << i << "," << j;
  }
  EXPECT_EQ(pixels_to_refine(f, false), std::vector<std::uint8_t>(18, 1));
}

// A pixel is compared with its 4 neighbours: a straight edge crossing a pixel leaves the neighbour
// along its normal's larger axis on its other side, so the diagonals found nothing more and
// refined a third more pixels (docs/scene-format.md, "Anti-aliasing").
TEST(Antialias, AdaptiveDecisionComparesTheFourNeighbours) {
  FrameBuffers f(3, 3);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      f.at(Channel::Depth, i, j) = i == 1 && j == 1 ? 2.0f : INFINITY;
      f.at(Channel::R, i, j) = f.at(Channel::G, i, j) = f.at(Channel::B, i, j) = 0.0f;
    }
  }
  const std::vector<std::uint8_t> refine = pixels_to_refine(f, true);
  EXPECT_EQ(refine, (std::vector<std::uint8_t>{0, 1, 0, 1, 1, 1, 0, 1, 0}));
}

struct Shape {
  const char* name;
  std::string sdf;
  std::function<std::pair<double, double>(double)> column;
};

std::vector<Shape> shapes() {
  return {{"disc", "{sphere: {radius: 1}}", [](double x) { return disc_column(x, 1.0); }},
          {"turned box", "{box: {half_size: [0.8, 0.8, 0.8], rotate: [0, 0, 30]}}",
           [](double x) { return square_column(x, 0.8, glm::radians(30.0)); }}};
}

TEST(Antialias, CoverageMatchesTheExactAreaOnBothBackends) {
  for (const Shape& shape : shapes()) {
    const std::vector<double> exact = exact_image(shape.column);
    for (bool adaptive : {true, false}) {
      const int samples = 16;
      const Scene scene = scene_from_yaml(high_contrast_scene(shape.sdf, samples, adaptive));
      const Scene one = scene_from_yaml(high_contrast_scene(shape.sdf, 1, adaptive));
      const FrameBuffers device = render_opencl(scene, {}).buffers;
      const FrameBuffers reference = render_reference(scene);
      const FrameBuffers single = render_opencl(one, {}).buffers;
      for (const FrameBuffers* f : {&device, &reference}) {
        const char* backend = f == &device ? "opencl" : "reference";
        for (std::size_t p = 0; p < exact.size(); ++p) {
          const float a = f->plane(Channel::A)[p];
          ASSERT_NEAR(a, exact[p], edge_error_bound(samples)) << shape.name << " " << backend << " pixel " << p;
          // The color is the coverage: white on black, ambient light only.
          ASSERT_NEAR(f->plane(Channel::R)[p], a, 1e-6) << shape.name << " " << backend << " pixel " << p;
          if (exact[p] == 1.0) {
            ASSERT_EQ(a, 1.0f) << "wholly inside: " << shape.name << " pixel " << p;
          }
          if (exact[p] == 0.0) {
            ASSERT_EQ(a, 0.0f) << "wholly outside: " << shape.name << " pixel " << p;
          }
        }
        // The target: at most a quarter of the one-sample error (measured, with its
        // numbers, by scripts/aa-bench.sh).
        EXPECT_LE(rms_error(f->plane(Channel::A), exact), 0.25 * rms_error(single.plane(Channel::A), exact))
            << shape.name << " " << backend;
      }
      // Centre-ray channels are the one-sample render's, bit for bit.
      for (Channel c : {Channel::Depth, Channel::Steps, Channel::NX, Channel::NY, Channel::NZ}) {
        EXPECT_EQ(device.plane(c), single.plane(c)) << shape.name << " " << kChannelNames[static_cast<int>(c)];
      }
      // Reference and kernel march the same sample rays; they may part only where a ray grazes.
      int apart = 0;
      for (std::size_t p = 0; p < exact.size(); ++p) {
        if (std::abs(device.plane(Channel::A)[p] - reference.plane(Channel::A)[p]) > 1.0f / samples + 1e-6f) ++apart;
      }
      EXPECT_LE(apart, 2) << shape.name;
    }
  }
}

TEST(Antialias, SamplesChannelCountsTheRaysAndAdaptiveSpendsThemAtEdges) {
  const Scene scene = scene_from_yaml(high_contrast_scene("{sphere: {radius: 1}}", 16, true));
  const FrameBuffers f = render_opencl(scene, {}).buffers;
  int refined = 0;
  for (float s : f.plane(Channel::Samples)) {
    ASSERT_TRUE(s == 1.0f || s == 16.0f) << s;
    refined += s == 16.0f;
  }
  // The disc's rim crosses about 2 pi r = 2 pi 9.9 = 62 pixels; both sides of it are refined.
  EXPECT_GT(refined, 60);
  EXPECT_LT(refined, 300);
}

TEST(Antialias, ChunksAndLanesRefineTheSamePixels) {
  const Scene scene =
      scene_from_yaml(high_contrast_scene("{box: {half_size: [0.8, 0.8, 0.8], rotate: [0, 0, 30]}}", 16, true));
  const FrameBuffers whole = render_opencl(scene, {}).buffers;
  OpenClOptions chunked;
  chunked.max_chunk_pixels = 32 * 8;  // four centre dispatches of 8 rows; one refining pass over them all
  const FrameBuffers parts = render_opencl(scene, chunked).buffers;
  for (Channel c : {Channel::R, Channel::A, Channel::Samples, Channel::Depth}) {
    EXPECT_EQ(parts.plane(c), whole.plane(c)) << kChannelNames[static_cast<int>(c)];
  }
  OpenClOptions one_lane;
  one_lane.lanes = 1;  // one packet per work-item
  const FrameBuffers single = render_opencl(scene, one_lane).buffers;
  EXPECT_EQ(single.plane(Channel::Samples), whole.plane(Channel::Samples));
  for (std::size_t p = 0; p < whole.plane(Channel::A).size(); ++p) {
    // The same rays; a lane's arithmetic may round a sample point's ray apart (fp contraction).
    EXPECT_NEAR(single.plane(Channel::A)[p], whole.plane(Channel::A)[p], 1.0 / 16 + 1e-6) << p;
  }
}

// The refining pass marches at most 262,144 (pixel, sample) pairs a dispatch: 200 x 180 pixels of
// 16 samples are 540,000 pairs (three dispatches, the last part-filled), whose results must land on
// their pixels as the reference's do, with 16 lanes a packet and with one.
TEST(Antialias, RefiningInSeveralDispatchesMatchesTheReference) {
  std::string yaml = high_contrast_scene("{box: {half_size: [0.8, 0.8, 0.8], rotate: [0, 0, 30]}}", 16, false);
  yaml.replace(yaml.find("width: 32, height: 32"), std::string("width: 32, height: 32").size(),
               "width: 200, height: 180");
  const Scene scene = scene_from_yaml(yaml);
  const FrameBuffers reference = render_reference(scene);
  for (int lanes : {16, 1}) {
    OpenClOptions options;
    options.lanes = lanes;
    const FrameBuffers device = render_opencl(scene, options).buffers;
    int apart = 0, partial = 0;
    for (std::size_t p = 0; p < reference.plane(Channel::A).size(); ++p) {
      const float a = device.plane(Channel::A)[p];
      partial += a > 0.0f && a < 1.0f;
      // The same rays; one may graze apart (as in CoverageMatchesTheExactAreaOnBothBackends).
      if (std::abs(a - reference.plane(Channel::A)[p]) > 1.0f / 16 + 1e-6f) ++apart;
      ASSERT_NEAR(device.plane(Channel::R)[p], a, 1e-6) << "lanes " << lanes << " pixel " << p;
    }
    EXPECT_LE(apart, 4) << "lanes " << lanes;
    // The square's side, 1.6 at 4.2 from the camera, spans 1.6 / 4.2 * 180 / (2 tan 22.5 deg) = 83
    // rows: its rim crosses at least 4 x 83 pixels, each partly covered.
    EXPECT_GT(partial, 300) << "lanes " << lanes;
  }
}

TEST(Antialias, OneSampleProgramHasNoAntialiasingCode) {
  Scene scene = scene_from_yaml(high_contrast_scene("{sphere: {radius: 1}}", 1, true));
  const KernelOptions options(KernelPurpose::Shaded, 16);
  EXPECT_EQ(generate_kernel_source(scene, options).find("#define ANTIALIAS"), std::string::npos);
  scene.render.samples = 4;
  EXPECT_NE(generate_kernel_source(scene, options).find("#define ANTIALIAS"), std::string::npos);
  EXPECT_EQ(generate_kernel_source(scene, KernelOptions(KernelPurpose::Ceiling, 16)).find("#define ANTIALIAS"),
            std::string::npos);
}

TEST(Antialias, BadSamplesAndAdaptiveAreErrorsAtTheirPlace) {
  const auto expect_error = [](const std::string& render, const std::string& message) {
    const std::string error = error_of("render: " + render + "\nsdf: {sphere: {radius: 1}}\n");
    EXPECT_NE(error.find("s.yaml:1:"), std::string::npos) << error;
    EXPECT_NE(error.find(message), std::string::npos) << error;
  };
  expect_error("{samples: 0}", "render.samples must be in [1, 1024] (got 0)");
  expect_error("{samples: -4}", "render.samples must be in [1, 1024] (got -4)");
  expect_error("{samples: 1025}", "render.samples must be in [1, 1024] (got 1025)");
  expect_error("{samples: 2.5}", "render.samples must be an integer");
  expect_error("{adaptive: 1}", "render.adaptive must be true or false (got '1')");
  expect_error("{adaptive: yes}", "render.adaptive must be true or false (got 'yes')");
  EXPECT_EQ(error_of("render: {samples: 1024, adaptive: false}\nsdf: {sphere: {radius: 1}}\n"), "no error");
}

TEST(Antialias, SamplesOptionOverridesTheSceneAndRejectsBadCounts) {
  testing::TempDir dir;
  const std::string scene = testing::source_path("scenes/torus.yaml").string();
  for (const char* bad : {"0", "-1", "2.5", "1025", "x"}) {
    const auto result =
        testing::run_clmarch({"render", scene, "--size", "16x16", "--samples", bad, "-o", (dir / "a.png").string()});
    EXPECT_EQ(result.exit_code, 2) << bad << ": " << result.err;
    EXPECT_NE(result.err.find("--samples"), std::string::npos) << result.err;
  }
  const auto ok = testing::run_clmarch({"render", scene, "--size", "16x16", "--samples", "4", "-o",
                                        (dir / "a.png").string(), "--set", "shading.view=samples"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(Antialias, HostMemoryCountsTheSampleBuffers) {
  EXPECT_GT(host_bytes_per_pixel(16), host_bytes_per_pixel(1));
  EXPECT_EQ(render_host_bytes(10, 10, 16), 100 * host_bytes_per_pixel(16));
}

}  // namespace
}  // namespace clmarch
