// The library layer (host/api/): a render session keeps its program across edits of numbers (at
// most two programs per shape), scene requests check their size and samples, and the field at
// points is the scene's distance on both backends.
#include "api/field.hpp"
#include "api/render_session.hpp"
#include "api/scene_request.hpp"
#include "common/errors.hpp"
#include "scene/scene_loader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace clmarch {
namespace {

const char* const kSphereOverFloor =
    "camera: {position: [0, 1.5, 5], look_at: [0, 0.5, 0]}\n"
    "render: {width: 40, height: 24, max_distance: 30, literals: LITERALS}\n"
    "sdf:\n  union:\n"
    "    - sphere: {center: [0, 0.6, 0], radius: RADIUS, color: [0.9, 0.2, 0.1]}\n"
    "    - plane: {normal: [0, 1, 0], offset: 0}\n"
    "lights: [{point: {position: [2, 3, 2]}}]\n";

Scene sphere_over_floor(const std::string& literals, const std::string& radius) {
  std::string yaml = kSphereOverFloor;
  yaml.replace(yaml.find("LITERALS"), 8, literals);
  yaml.replace(yaml.find("RADIUS"), 6, radius);
  return load_scene_text(yaml, "session.yaml");
}

TEST(RenderSession, AnEditedNumberBuildsOnceMoreThenNeverAgain) {
  RenderSession session;
  const FrameRequest request;
  const RenderResult first = session.render(sphere_over_floor("auto", "0.6"), request);
  EXPECT_EQ(first.stats.literals, "inline") << "the first scene of a shape spells its numbers";
  EXPECT_EQ(session.programs_built(), 1u);
  const RenderResult edited = session.render(sphere_over_floor("auto", "0.5"), request);
  EXPECT_EQ(edited.stats.literals, "buffer") << "an edited number moves them all to the values buffer";
  EXPECT_EQ(session.programs_built(), 2u);
  for (const char* radius : {"0.4", "0.55", "0.3"}) {
    const RenderResult again = session.render(sphere_over_floor("auto", radius), request);
    EXPECT_EQ(again.stats.build_ms, 0.0) << radius;
  }
  EXPECT_EQ(session.programs_built(), 2u) << "no later edit of a number builds";
  // The sphere shrank: the centre ray, which hit its top half, now travels farther.
  const auto centre_depth = [](const RenderResult& r) {
    return r.buffers.at(Channel::Depth, r.buffers.width / 2, r.buffers.height / 2);
  };
  EXPECT_GT(centre_depth(edited), centre_depth(first));

  session.render(sphere_over_floor("inline", "0.45"), request);
  EXPECT_EQ(session.programs_built(), 3u) << "render.literals: inline keeps its numbers spelled";
  FrameRequest on_the_reference;
  on_the_reference.backend = Backend::Reference;
  const RenderResult reference = session.render(sphere_over_floor("auto", "0.45"), on_the_reference);
  EXPECT_EQ(reference.stats.device, "CPU reference (double)");
  EXPECT_EQ(session.programs_built(), 3u);
}

TEST(RenderSession, BackendsByName) {
  EXPECT_EQ(parse_backend("opencl", "backend"), Backend::OpenCl);
  EXPECT_EQ(parse_backend("reference", "backend"), Backend::Reference);
  try {
    parse_backend("cuda", "--backend");
    FAIL() << "cuda is no backend";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--backend: backend must be opencl or reference (got 'cuda')");
  }
}

std::string request_error(const SceneRequest& request) {
  try {
    load_scene(request);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneRequest, TextSizeAndSamplesOverrideTheScene) {
  SceneRequest request;
  request.text = "sdf: {sphere: {radius: 1}}\n";
  request.source_name = "<text>";
  request.size = {{31, 17}};
  request.samples = 4;
  request.overrides = {{"render.epsilon", "1e-5"}};
  const Scene scene = load_scene(request);
  EXPECT_EQ(scene.render.width, 31);
  EXPECT_EQ(scene.render.height, 17);
  EXPECT_EQ(scene.render.samples, 4);
  EXPECT_EQ(scene.render.epsilon, 1e-5);

  request.size = {{0, 17}};
  request.size_label = "size";
  EXPECT_EQ(request_error(request),
            "size: size 0 x 17: width and height must be in [1, 65536] and their product at most 2147483647");
  request.size = {{65536, 65536}};
  EXPECT_NE(request_error(request).find("their product at most"), std::string::npos);
  request.size.reset();
  request.samples = 1025;
  EXPECT_EQ(request_error(request), "<text>: samples must be in [1, 1024] (got 1025)");
  request.samples.reset();
  request.text = "sdf: {sphere: {radius: -1}}\n";
  EXPECT_EQ(request_error(request).rfind("<text>:1:", 0), 0u) << request_error(request);
}

TEST(SampleField, IsTheSceneDistanceOnBothBackends) {
  const Scene scene =
      load_scene_text("sdf: {sphere: {center: [0.5, 0, 0], radius: 1.25, color: [0.2, 0.4, 0.6]}}\n", "field.yaml");
  const std::vector<glm::dvec3> points = {{0, 0, 0}, {3, 1, -2}, {0.5, 1.25, 0}, {-4, 4, 4}};
  for (Backend backend : {Backend::Reference, Backend::OpenCl}) {
    const FieldSamples samples = sample_field(scene, points, backend);
    ASSERT_EQ(samples.distance.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double offset = glm::length(points[i] - glm::dvec3(0.5, 0, 0));
      // Float rounding of the coordinates and of a length of at most 7.6 (OpenCL), or of the
      // double distance once (the reference): 8 ulps of the offset bound both.
      const double tolerance = 8 * std::numeric_limits<float>::epsilon() * offset;
      EXPECT_NEAR(samples.distance[i], offset - 1.25, tolerance) << kBackendNames[static_cast<int>(backend)] << i;
      EXPECT_FLOAT_EQ(samples.color[3 * i + 2], 0.6f);
      EXPECT_EQ(samples.id[i], 0.0f);
    }
  }
  const Scene tiled =
      load_scene_text("tiling: {cell: [4, 4, 4]}\nsdf: {sphere: {center: [2, 2, 2], radius: 1}}\n", "tiled.yaml");
  const FieldSamples wrapped = sample_field(tiled, {{2, 2, 2}, {6, -2, 10}}, Backend::Reference);
  EXPECT_EQ(wrapped.distance[0], wrapped.distance[1]) << "a tiled scene repeats its cell";
  EXPECT_TRUE(sample_field(scene, {}, Backend::OpenCl).distance.empty());
}

}  // namespace
}  // namespace clmarch
