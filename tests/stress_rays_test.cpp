// Rays that stress a sphere tracer (issue 7): grazing along planes and box faces, exactly along the
// axes (zero direction components), and cameras exactly on a surface, inside a solid and on a
// tiling cell's wall. Each pixel is either a hit within the exact depth bound or a miss by a
// documented rule, never garbage, and every render is repeatable bit for bit.
#include "analytic_intersections.hpp"
#include "check/cross_check.hpp"
#include "reference/reference_renderer.hpp"
#include "stress_support.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <functional>

namespace clmarch {
namespace {

using namespace stress;

/// First hit t* and |cos| between the ray and the surface there, in double; nothing on a miss.
struct ExactHit {
  double depth = 0.0;
  double cosine = 1.0;
};
using ExactIntersect = std::function<std::optional<ExactHit>(const glm::dvec3& o, const glm::dvec3& d)>;

/// Counts of how the pixels of a grazing render ended.
struct RuleCounts {
  int hits = 0;
  int far_misses = 0;
  int budget_misses = 0;
};

// Every pixel against the exact answer by the rule of docs/scene-format.md: a hit lies at most
// epsilon / cos in front of the surface and never behind it (exact fields), where cos is what the
// ray makes with the surface, however small (the bound is exact, not a grazing cut-off), plus float
// rounding; a miss is either a ray whose surface lies beyond max_distance or one that used its
// whole budget (steps == max_steps).
RuleCounts expect_hit_or_documented_miss(const Scene& scene, const FrameBuffers& b, const ExactIntersect& exact) {
  RuleCounts counts;
  for (int j = 0; j < b.height; ++j) {
    for (int i = 0; i < b.width; ++i) {
      const glm::dvec3 o = scene.camera.position, d = ray_direction(scene, i, j);
      const std::optional<ExactHit> truth = exact(o, d);
      const float depth = b.at(Channel::Depth, i, j);
      const float steps = b.at(Channel::Steps, i, j);
      const std::string where = fmt::format("pixel {},{} steps {}", i, j, steps);
      if (std::isfinite(depth)) {
        ++counts.hits;
        if (!truth) {
          ADD_FAILURE() << where << ": a hit where the ray meets nothing";
          continue;
        }
        const double rounding = kFloatRelative * (glm::length(o) + truth->depth);
        EXPECT_LE(truth->depth - depth, scene.render.epsilon / truth->cosine + rounding) << where;
        EXPECT_GE(truth->depth - depth, -rounding) << where;
      } else if (steps == static_cast<float>(scene.render.max_steps)) {
        ++counts.budget_misses;
      } else {
        ++counts.far_misses;
        // Leaving through max_distance: the surface, if any, is at least max_distance - eps/cos away.
        if (truth) {
          EXPECT_GE(truth->depth, scene.render.max_distance - scene.render.epsilon / truth->cosine) << where;
        }
      }
    }
  }
  return counts;
}

// A camera 0.05 above an endless floor looking at the horizon: the middle row (odd height) is
// exactly parallel to the floor, and the rows below meet it ever more obliquely, so sphere tracing
// converges like (1 - sin)^n and rays near the horizon run out of steps (plain sphere tracing).
TEST(GrazingRays, AlongAPlaneHitOrExhaustTheBudget) {
  const Scene scene = testing::scene_from_yaml(
      "camera: {position: [0, 0.05, 0], look_at: [0, 0.05, -10], fov: 60}\n"
      "render: {width: 48, height: 33, max_steps: 200, max_distance: 50, over_relaxation: 1}\n"
      "sdf: {plane: {normal: [0, 1, 0], offset: 0}}\n");
  const Plane floor{{0, 1, 0}, 0.0};
  for (int lanes : {1, 16}) {
    SCOPED_TRACE(fmt::format("lanes {}", lanes));
    const FrameBuffers b = render_checked(scene, KernelPurpose::Normals, lanes);
    const RuleCounts counts = expect_hit_or_documented_miss(scene, b, [&](const glm::dvec3& o, const glm::dvec3& d) {
      const std::optional<double> t = intersect_plane(o, d, floor);
      return t ? std::optional<ExactHit>(ExactHit{*t, std::abs(d.y)}) : std::nullopt;
    });
    EXPECT_GT(counts.hits, 0);
    EXPECT_GT(counts.budget_misses, 48) << "the horizon row and some rows below it should exhaust the budget";
    EXPECT_GT(counts.far_misses, 0);
    // The parallel row never gets nearer than 0.05: it marches 0.05 a step, 1000 steps to the limit.
    for (int i = 0; i < 48; ++i) EXPECT_EQ(b.at(Channel::Steps, i, 16), 200.0f) << i;
  }
}

// Normal used for the depth bound at a box hit: the best-aligned of the faces the point lies on
// (at an edge the march may stop in front of either face).
double box_cosine(const Box& box, const glm::dvec3& p, const glm::dvec3& d) {
  double best = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(std::abs(p[a] - box.center[a]) - box.half_size[a]) < 1e-9) best = std::max(best, std::abs(d[a]));
  }
  return best;
}

// The camera sits on the planes of the box's top face (y = 0.5) and side face (x = 0.5): the
// middle row runs along the top face, the middle column along the side face, and the centre pixel
// along the edge where they meet, to the box's corner.
TEST(GrazingRays, AlongBoxFacesAndEdges) {
  const Scene scene = testing::scene_from_yaml(
      "camera: {position: [0.5, 0.5, 3], look_at: [0.5, 0.5, 0], fov: 50}\n"
      "render: {width: 33, height: 33, max_steps: 300, max_distance: 20}\n"
      "sdf: {box: {half_size: [0.5, 0.5, 0.5]}}\n");
  const Box box{{0, 0, 0}, {0.5, 0.5, 0.5}};
  const auto exact = [&](const glm::dvec3& o, const glm::dvec3& d) -> std::optional<ExactHit> {
    const std::optional<double> t = intersect_box(o, d, box);
    if (!t) return std::nullopt;
    return ExactHit{*t, box_cosine(box, o + *t * d, d)};
  };
  for (int lanes : {1, 16}) {
    SCOPED_TRACE(fmt::format("lanes {}", lanes));
    const FrameBuffers b = render_checked(scene, KernelPurpose::Normals, lanes);
    const RuleCounts counts = expect_hit_or_documented_miss(scene, b, exact);
    EXPECT_GT(counts.hits, 33 * 33 / 5);
    // Along the edge to the corner (0.5, 0.5, 0.5): 2.5 away, and the ray sees the corner's front face head-on.
    EXPECT_NEAR(b.at(Channel::Depth, 16, 16), 2.5, scene.render.epsilon + 1e-6);
    // Rays along a face converge like head-on ones (the distance is to the face's front edge), so
    // none runs out of steps, and those of the middle row and column that meet the box hit it.
    EXPECT_EQ(counts.budget_misses, 0);
    int along_faces = 0;
    for (int k = 0; k <= 16; ++k)
      along_faces += std::isfinite(b.at(Channel::Depth, k, 16)) + std::isfinite(b.at(Channel::Depth, 16, 32 - k));
    EXPECT_GE(along_faces, 10);
  }
}

// Rays exactly along +-x, +-y, +-z through the centre pixel of an odd-sized image: the zero
// direction components must not produce NaN or a wrong depth. A unit sphere and a box each 4 away.
TEST(AxisRays, CentrePixelRunsAlongEachAxis) {
  const struct {
    const char* position;
    const char* up;
  } cameras[] = {{"[5, 0, 0]", "[0, 1, 0]"},  {"[-5, 0, 0]", "[0, 1, 0]"}, {"[0, 5, 0]", "[0, 0, 1]"},
                 {"[0, -5, 0]", "[0, 0, 1]"}, {"[0, 0, 5]", "[0, 1, 0]"},  {"[0, 0, -5]", "[0, 1, 0]"}};
  for (const char* shape : {"sphere: {radius: 1}", "box: {half_size: [1, 1, 1]}"}) {
    for (const auto& c : cameras) {
      SCOPED_TRACE(fmt::format("{} from {}", shape, c.position));
      const Scene scene = testing::scene_from_yaml(fmt::format(
          "camera: {{position: {}, look_at: [0, 0, 0], up: {}}}\nrender: {{width: 17, height: 9}}\nsdf: {{{}}}\n",
          c.position, c.up, shape));
      const glm::dvec3 centre_ray = ray_direction(scene, 8, 4);
      EXPECT_EQ(glm::length(glm::dvec3(centre_ray.x == 0.0, centre_ray.y == 0.0, centre_ray.z == 0.0)), std::sqrt(2.0))
          << "the centre ray should have two zero components";
      for (int lanes : {1, 16}) {
        const FrameBuffers b = render_checked(scene, KernelPurpose::Shaded, lanes);
        // Head-on, the march lands within epsilon in front of the surface at t = 4.
        EXPECT_LE(4.0 - b.at(Channel::Depth, 8, 4), scene.render.epsilon + kFloatRelative * 9.0);
        EXPECT_GE(4.0 - b.at(Channel::Depth, 8, 4), -kFloatRelative * 9.0);
        const glm::dvec3 n(b.at(Channel::NX, 8, 4), b.at(Channel::NY, 8, 4), b.at(Channel::NZ, 8, 4));
        EXPECT_GT(glm::dot(n, -centre_ray), 0.9999);
      }
    }
  }
}

/// The OpenCL render and the reference of scene: both keep the invariants and cross-check.
void expect_kernel_matches_reference(const Scene& scene) {
  const FrameBuffers opencl = render_checked(scene, KernelPurpose::Shaded);
  const FrameBuffers reference = render_reference(scene);
  EXPECT_EQ(invariant_violation(reference, scene.render.max_steps, true), "") << "reference";
  const CheckReport report = cross_check(scene, opencl, reference, reshade_hits(scene, opencl));
  EXPECT_TRUE(report.passed()) << report.to_text();
}

// The documented rule: a negative or zero distance counts as a hit, so a camera on a surface or
// inside a solid hits at depth 0 on its first step, in every pixel, looking any way.
TEST(CameraPlacement, OnASurfaceOrInsideEveryPixelHitsAtDepthZero) {
  const struct {
    const char* name;
    const char* yaml;
    bool zero_normal;  // the gradient vanishes at the camera (the sphere's centre)
  } cases[] = {
      {"on the sphere looking out", "camera: {position: [0, 0, 1], look_at: [0, 0, 3]}\nsdf: {sphere: {radius: 1}}\n",
       false},
      {"on the sphere looking along it",
       "camera: {position: [0, 0, 1], look_at: [1, 0, 1]}\nsdf: {sphere: {radius: 1}}\n", false},
      {"on the floor looking along it", "camera: {position: [0, 0, 0], look_at: [0, 0, -1]}\nsdf: {plane: {}}\n",
       false},
      {"at the sphere's centre", "camera: {position: [0, 0, 0], look_at: [0, 0, -1]}\nsdf: {sphere: {radius: 1}}\n",
       true},
      {"inside a box, off centre",
       "camera: {position: [0.2, 0.1, 0], look_at: [0, 0, -1]}\nsdf: {box: {half_size: [1, 1, 1]}}\n", false},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    Scene scene = testing::scene_from_yaml(
        std::string(c.yaml) + "render: {width: 24, height: 16}\nlights: [{directional: {direction: [1, 2, 3]}}]\n");
    const FrameBuffers b = render_checked(scene, KernelPurpose::Shaded);
    for (int j = 0; j < b.height; ++j) {
      for (int i = 0; i < b.width; ++i) {
        ASSERT_EQ(b.at(Channel::Depth, i, j), 0.0f) << i << "," << j;
        ASSERT_EQ(b.at(Channel::Steps, i, j), 1.0f) << i << "," << j;
        const double n =
            glm::length(glm::dvec3(b.at(Channel::NX, i, j), b.at(Channel::NY, i, j), b.at(Channel::NZ, i, j)));
        ASSERT_NEAR(n, c.zero_normal ? 0.0 : 1.0, 1e-5) << i << "," << j;
      }
    }
    expect_kernel_matches_reference(scene);
  }
}

// Under the cells tiling, a camera exactly on a cell wall, on an edge and at a corner (also at
// negative coordinates, where floor and truncation differ) starts in a well-defined cell and
// renders what the reference renders.
TEST(CameraPlacement, OnACellWallEdgeOrCorner) {
  for (const char* position : {"[3, 0.7, 0.3]", "[3, 1.5, 0.3]", "[3, 1.5, 1.5]", "[-2, -3, -0.75]", "[0, 0, 0]"}) {
    SCOPED_TRACE(position);
    const Scene scene =
        testing::scene_from_yaml(fmt::format("camera: {{position: {}, look_at: [5.2, 2.1, 4.4], fov: 60}}\n"
                                             "render: {{width: 48, height: 32, max_steps: 1000, max_distance: 30}}\n"
                                             "tiling: {{cell: [1, 1.5, 0.75]}}\n"
                                             "sdf: {{sphere: {{center: [0.5, 0.75, 0.375], radius: 0.3}}}}\n"
                                             "lights: [{{directional: {{direction: [1, 2, 3]}}}}]\n",
                                             position));
    expect_kernel_matches_reference(scene);
  }
}

}  // namespace
}  // namespace clmarch
