// The reference march against closed-form ray hits (sphere, box, plane, torus), plus the step-count
// semantics, the shading rules and the frame loop.
#include "analytic_intersections.hpp"
#include "reference/reference_renderer.hpp"
#include "reference/reference_sdf.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace clmarch {
namespace {

// Below this |cos| between ray and normal the ray grazes: the depth error eps/cos blows up and
// whether it hits at all depends on detail finer than epsilon.
constexpr double kMinCos = 0.05;
// t sums up to a few hundred doubles of magnitude < 16 (ulp 3.6e-15) and the closed forms are
// exact to ~1e-14; both far below the smallest epsilon tested.
constexpr double kDepthRounding = 1e-11;
// Normal components come from differences of O(10) distances over 2h = 2e-3.
constexpr double kNormalRounding = 1e-9;

const double kInf = std::numeric_limits<double>::infinity();

// A primitive with its closed-form first hit and normal.
struct AnalyticShape {
  std::string name;
  Node node;
  /// First hit of the shape grown outward by `grow` (the set of points within grow of it, or a
  /// superset of that set: a ray missing it stays farther than grow from the surface).
  std::function<std::optional<double>(const glm::dvec3&, const glm::dvec3&, double)> intersect;
  /// Outward unit normal at a surface point.
  std::function<glm::dvec3(const glm::dvec3&)> normal;
  /// Largest |principal curvature| of the surface.
  double curvature = 0.0;
  /// Whether the field is smooth within `width` of the surface point (finite differences valid).
  std::function<bool(const glm::dvec3&, double)> smooth_near = [](const glm::dvec3&, double) { return true; };
  std::vector<Camera> cameras;
};

using testing::leaf;

Camera camera_at(glm::dvec3 position, glm::dvec3 look_at) {
  Camera c;
  c.position = position;
  c.look_at = look_at;
  return c;
}

AnalyticShape sphere_shape() {
  const Sphere s{{0.1, -0.2, 0.3}, 1.0};
  AnalyticShape a;
  a.name = "sphere";
  a.node = leaf(s, NodeKind::Sphere);
  a.intersect = [s](auto o, auto d, double g) { return intersect_sphere(o, d, Sphere{s.center, s.radius + g}); };
  a.normal = [s](const glm::dvec3& x) { return glm::normalize(x - s.center); };
  a.curvature = 1.0 / s.radius;
  a.cameras = {Camera{}, camera_at({0.0, 0.0, 3.0}, {0.4, 0.1, 0.0})};
  return a;
}

AnalyticShape box_shape() {
  const Box b{{0.2, 0.0, -0.1}, {0.5, 0.75, 1.0}};
  // The face a surface point lies on: the axis where it is farthest out of the box.
  const auto face_axis = [b](const glm::dvec3& x) {
    const glm::dvec3 q = glm::abs(x - b.center) - b.half_size;
    return q.x >= q.y && q.x >= q.z ? 0 : (q.y >= q.z ? 1 : 2);
  };
  AnalyticShape a;
  a.name = "box";
  a.node = leaf(b, NodeKind::Box);
  a.intersect = [b](auto o, auto d, double g) { return intersect_box(o, d, Box{b.center, b.half_size + g}); };
  a.normal = [b, face_axis](const glm::dvec3& x) {
    glm::dvec3 n(0.0);
    const int i = face_axis(x);
    n[i] = x[i] > b.center[i] ? 1.0 : -1.0;
    return n;
  };
  // Stencils straddling an edge see two faces.
  a.smooth_near = [b, face_axis](const glm::dvec3& x, double width) {
    const int i = face_axis(x);
    for (int j = 0; j < 3; ++j) {
      if (j != i && std::abs(x[j] - b.center[j]) > b.half_size[j] - width) return false;
    }
    return true;
  };
  a.cameras = {Camera{}, camera_at({2.5, -1.0, 1.5}, {0.0, 0.0, 0.0})};
  return a;
}

AnalyticShape plane_shape() {
  const Plane p{glm::normalize(glm::dvec3(0.1, 1.0, 0.05)), 0.5};
  AnalyticShape a;
  a.name = "plane";
  a.node = leaf(p, NodeKind::Plane);
  a.intersect = [p](auto o, auto d, double g) { return intersect_plane(o, d, Plane{p.normal, p.offset - g}); };
  a.normal = [p](const glm::dvec3&) { return p.normal; };
  // Looking level: the upper half misses, rows near the horizon hit beyond max_distance.
  a.cameras = {camera_at({0.0, 1.0, 5.0}, {0.0, 1.0, 0.0}), Camera{}};
  return a;
}

AnalyticShape torus_shape() {
  const Torus t{{0.0, 0.0, 0.0}, 1.0, 0.25};
  AnalyticShape a;
  a.name = "torus";
  a.node = leaf(t, NodeKind::Torus);
  a.intersect = [t](auto o, auto d, double g) {
    return intersect_torus(o, d, Torus{t.center, t.major_radius, t.minor_radius + g});
  };
  a.normal = [t](const glm::dvec3& x) {
    const glm::dvec3 q = x - t.center;
    const glm::dvec3 ring = t.major_radius * glm::normalize(glm::dvec3(q.x, 0.0, q.z));
    return glm::normalize(q - ring);
  };
  a.curvature = 1.0 / t.minor_radius;
  // The low camera looks through the hole at the far side: several roots per ray.
  a.cameras = {Camera{}, camera_at({0.3, 0.4, 4.0}, {0.0, 0.0, 0.0})};
  return a;
}

Scene scene_of(const AnalyticShape& shape, double epsilon, NormalMethod method) {
  Scene s;
  s.sdf = shape.node;
  s.render.epsilon = epsilon;
  s.render.max_steps = 2000;
  s.render.normal_method = method;
  return s;
}

struct Tally {
  int hits = 0, misses = 0, skipped = 0;
};

// Compares one reference ray with the closed form where the answer is robust; counts the rest.
void check_ray(const AnalyticShape& shape, const Scene& scene, const glm::dvec3& o, const glm::dvec3& d, Tally& tally) {
  const RenderSettings& rs = scene.render;
  // A ray that stays farther than epsilon from the surface never sees a distance below epsilon.
  const double grow = 2.0 * rs.epsilon;
  const auto t_hit = shape.intersect(o, d, 0.0);
  const auto t_grown = shape.intersect(o, d, grow);
  const RayResult r = reference_trace(scene, o, d);
  if (!t_grown || *t_grown >= rs.max_distance) {
    ++tally.misses;
    EXPECT_FALSE(r.hit) << "depth " << r.depth;
    EXPECT_EQ(r.depth, kInf);
    EXPECT_EQ(r.normal, glm::dvec3(0.0));
    return;
  }
  if (!t_hit || *t_hit >= rs.max_distance) {
    ++tally.skipped;
    return;
  }
  const glm::dvec3 x = o + *t_hit * d;
  const glm::dvec3 n = shape.normal(x);
  const double cos = -glm::dot(n, d);
  // The grown shape entered well before the hit: the ray skims another part of the surface first.
  if (cos < kMinCos || *t_hit - *t_grown > 1.5 * grow / cos) {
    ++tally.skipped;
    return;
  }
  ++tally.hits;
  ASSERT_TRUE(r.hit) << "expected depth " << *t_hit << ", cos " << cos << ", steps " << r.steps;
  // The march stops at the first point within epsilon, on the near side: the distance there is
  // at least (t_hit - t) cos less a curvature term of the surface between that point and the hit.
  const double first_order = rs.epsilon / cos;
  const double max_error = first_order + shape.curvature * first_order * first_order / cos;
  EXPECT_LE(r.depth, *t_hit + kDepthRounding);
  EXPECT_GE(r.depth, *t_hit - max_error - kDepthRounding) << "cos " << cos;
  EXPECT_LE(r.steps, rs.max_steps);

  // Finite differences: central is second order, ~(h kappa)^2; tetrahedral only first order, its
  // error is h times the Hessian's off-diagonal entries (<= kappa). Twice each leading term, plus the
  // turn of the normal between the march point and the hit.
  const double h = rs.normal_epsilon;
  const double hk = h * shape.curvature;
  const double stencil = rs.normal_method == NormalMethod::Central ? 2.0 * hk * hk : 2.0 * hk;
  if (shape.smooth_near(x, 2.0 * h + max_error)) {
    EXPECT_LE(glm::length(r.normal - n), stencil + shape.curvature * max_error + kNormalRounding)
        << "normal (" << r.normal.x << ", " << r.normal.y << ", " << r.normal.z << ") vs (" << n.x << ", " << n.y
        << ", " << n.z << ")";
  }
}

// Hand-picked rays: along the axes, down the torus tube and out of its hole, diagonals. Rays that
// start inside a shape are skipped by check_ray (cos < 0 at the exit).
std::vector<std::pair<glm::dvec3, glm::dvec3>> hand_picked_rays() {
  return {
      {{0.0, 0.0, 5.0}, {0.0, 0.0, -1.0}},
      {{-4.0, 0.0, 0.0}, {1.0, 0.0, 0.0}},
      {{0.0, 5.0, 0.0}, {0.0, -1.0, 0.0}},
      {{1.0, 3.0, 0.0}, {0.0, -1.0, 0.0}},
      {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}},
      {{0.0, 0.1, 4.0}, glm::normalize(glm::dvec3(0.05, -0.02, -1.0))},
      {{3.0, 3.0, 3.0}, glm::normalize(glm::dvec3(-1.0))},
      {{0.0, 2.0, 0.0}, glm::normalize(glm::dvec3(1.0, 1.0, 0.0))},
  };
}

class ReferenceMarch : public ::testing::TestWithParam<double> {};

// Every pixel of a small image per camera, and the hand-picked rays, for each normal method.
TEST_P(ReferenceMarch, MatchesClosedFormHits) {
  const double epsilon = GetParam();
  for (const AnalyticShape& shape : {sphere_shape(), box_shape(), plane_shape(), torus_shape()}) {
    for (NormalMethod method : {NormalMethod::Central, NormalMethod::Tetrahedral}) {
      const Scene scene = scene_of(shape, epsilon, method);
      Tally tally;
      for (const Camera& camera : shape.cameras) {
        const CameraBasis basis = camera_basis(camera, 40, 30);
        for (int j = 0; j < basis.height; ++j) {
          for (int i = 0; i < basis.width; ++i) {
            SCOPED_TRACE(shape.name + " pixel " + std::to_string(i) + "," + std::to_string(j));
            check_ray(shape, scene, basis.origin, pixel_ray_direction(basis, i, j), tally);
          }
        }
      }
      for (const auto& [o, d] : hand_picked_rays()) {
        SCOPED_TRACE(shape.name + " hand-picked ray");
        check_ray(shape, scene, o, d, tally);
      }
      // The comparison must not be vacuous: most rays are decided, and both outcomes occur.
      const int total = tally.hits + tally.misses + tally.skipped;
      EXPECT_LE(tally.skipped, total / 20) << shape.name;
      EXPECT_GE(tally.hits, total / 10) << shape.name;
      EXPECT_GE(tally.misses, total / 10) << shape.name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Epsilons, ReferenceMarch, ::testing::Values(1e-9, RenderSettings{}.epsilon));

TEST(AnalyticIntersections, KnownHits) {
  const Sphere unit{{0.0, 0.0, 0.0}, 1.0};
  EXPECT_DOUBLE_EQ(*intersect_sphere({0.0, 0.0, 5.0}, {0.0, 0.0, -1.0}, unit), 4.0);
  EXPECT_DOUBLE_EQ(*intersect_sphere({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, unit), 1.0);  // inside: exit
  EXPECT_DOUBLE_EQ(*intersect_sphere({0.0, 0.0, 5.0}, {0.0, 0.0, -2.0}, unit), 2.0);  // d not unit
  EXPECT_FALSE(intersect_sphere({0.0, 0.0, 5.0}, {0.0, 0.0, 1.0}, unit));
  EXPECT_FALSE(intersect_sphere({0.0, 1.5, 5.0}, {0.0, 0.0, -1.0}, unit));

  const Box box{{1.0, 0.0, 0.0}, {0.5, 1.0, 2.0}};
  EXPECT_DOUBLE_EQ(*intersect_box({-3.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, box), 3.5);
  EXPECT_DOUBLE_EQ(*intersect_box({1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, box), 2.0);   // inside: exit
  EXPECT_DOUBLE_EQ(*intersect_box({1.0, 1.0, 5.0}, {0.0, 0.0, -1.0}, box), 3.0);  // along a face
  EXPECT_FALSE(intersect_box({-3.0, 1.5, 0.0}, {1.0, 0.0, 0.0}, box));
  EXPECT_FALSE(intersect_box({-3.0, 0.0, 0.0}, {-1.0, 0.0, 0.0}, box));

  const Plane floor{{0.0, 1.0, 0.0}, 1.0};  // y = -1
  EXPECT_DOUBLE_EQ(*intersect_plane({0.0, 2.0, 0.0}, glm::normalize(glm::dvec3(1.0, -1.0, 0.0)), floor),
                   3.0 * std::sqrt(2.0));
  EXPECT_FALSE(intersect_plane({0.0, 2.0, 0.0}, {1.0, 0.0, 0.0}, floor));
  EXPECT_FALSE(intersect_plane({0.0, 2.0, 0.0}, {0.0, 1.0, 0.0}, floor));

  const Torus torus{{0.0, 0.0, 0.0}, 1.0, 0.25};
  EXPECT_NEAR(*intersect_torus({-4.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, torus), 2.75, 1e-14);
  EXPECT_NEAR(*intersect_torus({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, torus), 0.75, 1e-14);   // from the hole
  EXPECT_NEAR(*intersect_torus({1.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, torus), 0.25, 1e-14);   // inside: exit
  EXPECT_NEAR(*intersect_torus({1.0, 3.0, 0.0}, {0.0, -1.0, 0.0}, torus), 2.75, 1e-14);  // down the tube
  EXPECT_NEAR(*intersect_torus({0.0, 0.2, 4.0}, {0.0, 0.0, -1.0}, torus), 4.0 - 1.0 - std::sqrt(0.25 * 0.25 - 0.04),
              1e-14);
  EXPECT_FALSE(intersect_torus({0.0, 5.0, 0.0}, {0.0, -1.0, 0.0}, torus));  // down the axis
  EXPECT_FALSE(intersect_torus({-4.0, 0.3, 0.0}, {1.0, 0.0, 0.0}, torus));  // above it
}

// The torus root isolation on random rays: every hit lies on the surface, and no earlier point of
// the ray is inside the solid.
TEST(AnalyticIntersections, TorusHitsLieOnTheSurface) {
  const Torus torus{{0.2, -0.1, 0.3}, 1.0, 0.3};
  const auto implicit = [&](const glm::dvec3& x) {
    const glm::dvec3 q = x - torus.center;
    return glm::length(glm::dvec2(glm::length(glm::dvec2(q.x, q.z)) - torus.major_radius, q.y)) - torus.minor_radius;
  };
  int hits = 0;
  for (int i = 0; i < 400; ++i) {
    const double a = i * 0.61803398875 * 2.0 * std::numbers::pi, b = std::acos(1.0 - 2.0 * ((i + 0.5) / 400.0));
    const glm::dvec3 o = 3.0 * glm::dvec3(std::sin(b) * std::cos(a), std::cos(b), std::sin(b) * std::sin(a));
    const glm::dvec3 d = glm::normalize(glm::dvec3(0.3 * std::sin(7.0 * i), 0.2 * std::cos(5.0 * i), 0.0) - o);
    const auto t = intersect_torus(o, d, torus);
    if (!t) continue;
    ++hits;
    EXPECT_NEAR(implicit(o + *t * d), 0.0, 1e-12);
    for (int k = 0; k < 64; ++k) EXPECT_GT(implicit(o + (*t * k / 64.0) * d), 0.0);
  }
  EXPECT_GT(hits, 100);
}

// The floor y = 0 under default settings; along the rays used here every distance is exact in binary.
// The floor y = 0, marched by plain sphere tracing.
Scene floor_scene() {
  Scene s;
  s.sdf = leaf(Plane{{0.0, 1.0, 0.0}, 0.0}, NodeKind::Plane);
  s.render.over_relaxation = 1.0;
  return s;
}

TEST(ReferenceTrace, HeadOnHitTakesTwoSteps) {
  const Scene s = floor_scene();
  const RayResult r = reference_trace(s, {0.0, 2.0, 0.0}, {0.0, -1.0, 0.0});
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.depth, 2.0);
  EXPECT_EQ(r.steps, 2);  // d = 2 at t = 0, then d = 0 at t = 2
  EXPECT_EQ(r.normal, glm::dvec3(0.0, 1.0, 0.0));
}

// At 60 degrees from the normal every step halves the height: d_k = 0.5^k, so the first distance
// below 1e-4 is d_14, the 15th evaluation, at t = 2 (1 - 0.5^14).
TEST(ReferenceTrace, ObliqueStepsFollowTheGeometricSeries) {
  Scene s = floor_scene();
  const glm::dvec3 o(0.0, 1.0, 0.0), d(std::sqrt(3.0) / 2.0, -0.5, 0.0);
  const RayResult r = reference_trace(s, o, d);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.steps, 15);
  EXPECT_EQ(r.depth, 2.0 * (1.0 - std::pow(0.5, 14)));
  s.render.max_steps = 15;
  EXPECT_TRUE(reference_trace(s, o, d).hit);
  s.render.max_steps = 14;  // the budget runs out one evaluation short: a miss
  const RayResult out = reference_trace(s, o, d);
  EXPECT_FALSE(out.hit);
  EXPECT_EQ(out.steps, 14);
  EXPECT_EQ(out.depth, kInf);
}

// Marching away from the floor doubles t + 1 each step: t = 0, 1, 3, 7, ..., 2^k - 1.
TEST(ReferenceTrace, MissThroughMaxDistance) {
  Scene s = floor_scene();
  s.shading.background = {0.2, 0.3, 0.4};
  const glm::dvec3 o(0.0, 1.0, 0.0), up(0.0, 1.0, 0.0);
  RayResult r = reference_trace(s, o, up);
  EXPECT_FALSE(r.hit);
  EXPECT_EQ(r.steps, 7);  // t = 63 + 64 = 127 >= 100 after the 7th evaluation
  EXPECT_EQ(r.depth, kInf);
  EXPECT_EQ(r.normal, glm::dvec3(0.0));
  EXPECT_EQ(r.color, s.shading.background);
  s.render.max_distance = 63.0;  // reaching max_distance exactly already misses
  EXPECT_EQ(reference_trace(s, o, up).steps, 6);
  s.render.max_steps = 3;
  EXPECT_EQ(reference_trace(s, o, up).steps, 3);
}

TEST(ReferenceTrace, StartingInsideHitsAtZero) {
  const RayResult r = reference_trace(floor_scene(), {0.0, -1.0, 0.0}, {1.0, 0.0, 0.0});
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.depth, 0.0);
  EXPECT_EQ(r.steps, 1);
}

// Shading closed forms on the floor: view straight down, one light at 60 degrees from the normal.
class ReferenceShading : public ::testing::Test {
 protected:
  void SetUp() override {
    scene = floor_scene();
    scene.sdf.color = albedo;
    scene.shading.ambient = {0.1, 0.2, 0.3};
    scene.shading.diffuse = 0.8;
    scene.shading.specular = 0.5;
    scene.shading.shininess = 4.0;
    Light light;
    light.kind = LightKind::Directional;
    light.direction = {std::sqrt(3.0) / 2.0, 0.5, 0.0};
    light.color = {1.0, 0.5, 0.25};
    light.intensity = 2.0;
    scene.lights = {light};
  }
  glm::dvec3 shade() const { return reference_trace(scene, {0.0, 2.0, 0.0}, {0.0, -1.0, 0.0}).color; }
  glm::dvec3 lambert() const {
    return albedo * scene.shading.ambient + albedo * glm::dvec3(2.0, 1.0, 0.5) * (0.8 * 0.5);
  }
  void expect_color(const glm::dvec3& got, const glm::dvec3& want) const {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], kShadingRounding) << "channel " << c;
  }
  // A dozen double operations on O(1) values.
  static constexpr double kShadingRounding = 1e-12;
  const glm::dvec3 albedo{0.8, 0.6, 0.4};
  Scene scene;
};

TEST_F(ReferenceShading, Lambert) { expect_color(shade(), lambert()); }

TEST_F(ReferenceShading, PhongHighlightIsCosineOfTheMirrorAngle) {
  scene.shading.model = ShadingModel::Phong;
  // reflect(-l, n) is 60 degrees from the view direction: s = cos(60)^4.
  expect_color(shade(), lambert() + glm::dvec3(2.0, 1.0, 0.5) * (0.5 * std::pow(0.5, 4)));
}

TEST_F(ReferenceShading, BlinnPhongHighlightIsCosineOfTheHalfAngle) {
  scene.shading.model = ShadingModel::BlinnPhong;
  // The half vector is 30 degrees from the normal: s = cos(30)^4 = 9/16.
  expect_color(shade(), lambert() + glm::dvec3(2.0, 1.0, 0.5) * (0.5 * 9.0 / 16.0));
}

TEST_F(ReferenceShading, LightsBelowTheSurfaceAddNothing) {
  // Blinn-Phong's half vector would still face the normal: only the n.l > 0 rule removes it.
  scene.shading.model = ShadingModel::BlinnPhong;
  scene.lights[0].direction = {0.8, -0.6, 0.0};
  expect_color(shade(), albedo * scene.shading.ambient);
}

TEST_F(ReferenceShading, PointLightsAndSeveralLightsAdd) {
  Light point;
  point.position = {0.0, 5.0, 0.0};  // straight above the hit at the origin: n.l = 1
  point.intensity = 0.5;
  scene.lights.push_back(point);
  expect_color(shade(), lambert() + albedo * (0.8 * 0.5));
}

TEST_F(ReferenceShading, StepOcclusionThenClamp) {
  scene.shading.step_ao = 40.0;  // 2 steps: subtract 4 / 40
  expect_color(shade(), lambert() - 0.1);
  scene.shading.step_ao = 1.0;
  expect_color(shade(), glm::dvec3(0.0));
}

TEST_F(ReferenceShading, AlbedoComesFromTheHitColor) {
  Node red = leaf(Sphere{{0.0, 0.0, 0.0}, 0.5}, NodeKind::Sphere);
  red.color = glm::dvec3(1.0, 0.0, 0.0);
  Node both;
  both.kind = NodeKind::Union;
  both.children = {scene.sdf, red};
  scene.sdf = both;
  scene.lights.clear();
  expect_color(reference_trace(scene, {0.0, 2.0, 0.0}, {0.0, -1.0, 0.0}).color, glm::dvec3(0.1, 0.0, 0.0));
  expect_color(reference_trace(scene, {3.0, 2.0, 0.0}, {0.0, -1.0, 0.0}).color, albedo * scene.shading.ambient);
}

// A lit scene with every feature on; the frame must be reference_trace through each pixel centre.
Scene small_lit_scene() {
  Scene s;
  Node ball = leaf(Sphere{{0.3, 0.5, 0.0}, 0.6}, NodeKind::Sphere);
  ball.color = glm::dvec3(0.9, 0.2, 0.1);
  Node ring = leaf(Torus{{0.0, 0.0, 0.0}, 0.8, 0.2}, NodeKind::Torus);
  ring.transform.rotate_degrees = {30.0, 0.0, 0.0};
  Node ground = leaf(Plane{{0.0, 1.0, 0.0}, 0.5}, NodeKind::Plane);
  s.sdf.kind = NodeKind::SmoothUnion;
  s.sdf.params = SmoothUnion{0.2};
  s.sdf.children = {ball, ring, ground};
  s.camera = camera_at({1.0, 1.5, 4.0}, {0.0, 0.2, 0.0});
  s.render.width = 13;
  s.render.height = 7;
  s.render.normal_method = NormalMethod::Tetrahedral;
  s.shading.model = ShadingModel::BlinnPhong;
  s.shading.specular = 0.4;
  s.shading.step_ao = 5000.0;
  s.shading.background = {0.05, 0.1, 0.2};
  Light sun;
  sun.kind = LightKind::Directional;
  sun.direction = glm::normalize(glm::dvec3(0.3, 1.0, 0.5));
  Light lamp;
  lamp.position = {-2.0, 3.0, 2.0};
  lamp.color = {1.0, 0.8, 0.6};
  s.lights = {sun, lamp};
  return s;
}

TEST(RenderReference, EveryPixelIsItsRay) {
  const Scene s = small_lit_scene();
  const FrameBuffers fb = render_reference(s);
  ASSERT_EQ(fb.width, 13);
  ASSERT_EQ(fb.height, 7);
  const CameraBasis basis = camera_basis(s.camera, s.render.width, s.render.height);
  int hits = 0;
  for (int j = 0; j < fb.height; ++j) {
    for (int i = 0; i < fb.width; ++i) {
      const RayResult r = reference_trace(s, basis.origin, pixel_ray_direction(basis, i, j));
      hits += r.hit;
      // wall_steps 0 (no tiling); the primitive hit or -1; the layers; depth.lo 0 (a float
      // render); its status; one ray per pixel: A is the hit, samples 1.
      const LightTerms& l = r.layers;
      const double want[kChannelCount] = {
          r.color.r,        r.color.g,         r.color.b,    r.depth,      double(r.steps),
          r.normal.x,       r.normal.y,        r.normal.z,   0.0,          r.hit ? double(r.primitive) : -1.0,
          l.ambient.r,      l.ambient.g,       l.ambient.b,  l.diffuse.r,  l.diffuse.g,
          l.diffuse.b,      l.specular.r,      l.specular.g, l.specular.b, 0.0,
          double(r.status), r.hit ? 1.0 : 0.0, 1.0};
      for (int c = 0; c < kChannelCount; ++c) {
        EXPECT_EQ(fb.at(Channel(c), i, j), static_cast<float>(want[c])) << kChannelNames[c] << " at " << i << "," << j;
      }
    }
  }
  EXPECT_GT(hits, 10);
  EXPECT_LT(hits, 13 * 7);
}

// The reference's own hits, shaded again from their (float) depth, normal and steps, keep their
// colors, also where the point must be found in its tiling cell (both tilings; under the cells
// tiling with the camera in another cell than the lights), on mirrors and under normal-marched
// occlusion: only pixels the rounding of the depth moves across a shadow's or a material's edge
// may change, one in a thousand at most.
TEST(ReshadeHits, TheReferencesOwnHitsKeepTheirColors) {
  const std::vector<std::pair<std::string, std::vector<SceneOverride>>> cases = {
      {"tiled_spheres.yaml", {{"camera.position", "[7.5, 0.15, -2.95]"}, {"camera.look_at", "[10.2, 1.9, 1.1]"}}},
      {"tiled_boxes.yaml", {{"tiling.method", "mod"}}},
      {"lava_lamp.yaml", {}},
      {"sphere_shadows.yaml", {}}};
  for (const auto& [name, overrides] : cases) {
    Scene scene = load_scene_file(testing::source_path("scenes/" + name).string(), overrides);
    scene.render.width = 96;
    scene.render.height = 54;
    const FrameBuffers reference = render_reference(scene);
    const FrameBuffers reshaded = reshade_hits(scene, reference);
    int hits = 0, changed = 0;
    for (int j = 0; j < reference.height; ++j) {
      for (int i = 0; i < reference.width; ++i) {
        for (int c = 3; c < kChannelCount; ++c) {
          // The layers are the shading's, computed again like the color.
          if (std::find(std::begin(kLayerChannels), std::end(kLayerChannels), Channel(c)) != std::end(kLayerChannels))
            continue;
          EXPECT_EQ(reshaded.at(Channel(c), i, j), reference.at(Channel(c), i, j))
              << name << " copies " << kChannelNames[c];
        }
        if (!std::isfinite(reference.at(Channel::Depth, i, j))) {
          EXPECT_EQ(reshaded.at(Channel::R, i, j), reference.at(Channel::R, i, j))
              << name << ": a miss keeps its color";
          continue;
        }
        ++hits;
        float diff = 0.0f;
        for (Channel c : {Channel::R, Channel::G, Channel::B})
          diff = std::max(diff, std::abs(reshaded.at(c, i, j) - reference.at(c, i, j)));
        for (Channel c : kLayerChannels) diff = std::max(diff, std::abs(reshaded.at(c, i, j) - reference.at(c, i, j)));
        changed += diff > 1e-4f;
      }
    }
    EXPECT_GT(hits, 96 * 54 / 4) << name;
    EXPECT_LE(changed, 96 * 54 / 1000) << name;
  }
}

// A ball up-left and a box down-right of the view centre: catches flipped or transposed images.
// Every pixel centre is at least 0.02 from a silhouette (checked against the closed forms).
TEST(RenderReference, GoldenHitMask) {
  const char* const kGolden[] = {
      "................", "................", "....###.........", "...#####........",
      "...#####........", "...#####........", "....###...###...", "..........###...",
      "..........###...", "................", "................", "................",
  };
  Scene s;
  s.sdf.kind = NodeKind::Union;
  s.sdf.children = {leaf(Sphere{{-0.7, 0.4, 0.0}, 0.7}, NodeKind::Sphere),
                    leaf(Box{{0.9, -0.4, 0.0}, {0.4, 0.3, 0.3}}, NodeKind::Box)};
  s.camera = camera_at({0.0, 0.0, 4.0}, {0.0, 0.0, 0.0});
  s.render.width = 16;
  s.render.height = 12;
  const FrameBuffers fb = render_reference(s);
  for (int j = 0; j < fb.height; ++j) {
    std::string row;
    for (int i = 0; i < fb.width; ++i) row += std::isfinite(fb.at(Channel::Depth, i, j)) ? '#' : '.';
    EXPECT_EQ(row, kGolden[j]) << "row " << j;
  }
}

}  // namespace
}  // namespace clmarch
