// Exact-depth renders on the OpenCL device: scenes of one sphere, box or plane compared pixel by
// pixel with closed-form ray intersections in double precision.
#include "analytic_intersections.hpp"
#include "reference/reference_renderer.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/camera_model.hpp"
#include "support/test_support.hpp"
#include "support/tolerances.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <vector>

namespace clmarch {
namespace {

using testing::kFloatRelative;
// Grazing rays may legitimately run out of steps, so they count with the silhouette.
using testing::kGrazingCosine;
using testing::scene_from_yaml;

using Intersect = std::function<std::optional<double>(const glm::dvec3&, const glm::dvec3&)>;
using NormalAt = std::function<glm::dvec3(const glm::dvec3&)>;

struct DepthCase {
  std::string name;
  std::string scene_yaml;
  Intersect intersect;
  NormalAt normal_at;
  /// Which object holds the surface point, for scenes of several; none: one object.
  std::function<int(const glm::dvec3&)> object_at;
};

struct PixelTruth {
  bool hit = false;
  /// Which object of the scene the ray hits (DepthCase::object_at).
  int object = 0;
  double depth = 0.0;
  double cosine = 0.0;
};

/// What each pixel's ray meets by the closed form, row-major.
std::vector<PixelTruth> pixel_truths(const DepthCase& c, const Scene& scene) {
  const CameraBasis basis = camera_basis(scene.camera, scene.render.width, scene.render.height);
  const int w = scene.render.width, h = scene.render.height;
  std::vector<PixelTruth> truth(static_cast<std::size_t>(w) * h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const glm::dvec3 dir = pixel_ray_direction(basis, i, j);
      PixelTruth& t = truth[static_cast<std::size_t>(j) * w + i];
      const std::optional<double> hit = c.intersect(basis.origin, dir);
      t.hit = hit && *hit < scene.render.max_distance;
      if (t.hit) {
        t.depth = *hit;
        t.cosine = std::abs(glm::dot(dir, c.normal_at(basis.origin + *hit * dir)));
        if (c.object_at) t.object = c.object_at(basis.origin + *hit * dir);
      }
    }
  }
  return truth;
}

/// Whether pixel (i, j) of an image of width w and height h grazes its surface or neighbours a
/// pixel that meets something else.
bool near_silhouette(const std::vector<PixelTruth>& truth, int w, int h, int i, int j) {
  const PixelTruth& t = truth[static_cast<std::size_t>(j) * w + i];
  if (t.hit && t.cosine < kGrazingCosine) return true;
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) {
      const int ni = i + di, nj = j + dj;
      if (ni < 0 || nj < 0 || ni >= w || nj >= h) continue;
      // Another object's edge is a silhouette as much as a miss is: a ray grazing it within
      // epsilon may stop there.
      const PixelTruth& n = truth[static_cast<std::size_t>(nj) * w + ni];
      if (n.hit != t.hit || n.object != t.object) return true;
    }
  }
  return false;
}

void check_exact_depth(const DepthCase& c, int lanes) {
  Scene scene = scene_from_yaml(c.scene_yaml);
  scene.render.width = 96;
  scene.render.height = 64;
  OpenClOptions options;
  options.lanes = lanes;
  options.purpose = KernelPurpose::DepthSteps;
  const FrameBuffers buffers = render_opencl(scene, options).buffers;
  const CameraBasis basis = camera_basis(scene.camera, scene.render.width, scene.render.height);
  const int w = scene.render.width, h = scene.render.height;
  const std::vector<PixelTruth> truth = pixel_truths(c, scene);
  int compared = 0, hits = 0;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      if (near_silhouette(truth, w, h, i, j)) continue;
      const PixelTruth& t = truth[static_cast<std::size_t>(j) * w + i];
      ++compared;
      const float depth = buffers.at(Channel::Depth, i, j);
      ASSERT_EQ(std::isfinite(depth), t.hit) << c.name << " lanes " << lanes << " pixel " << i << "," << j;
      if (!t.hit) continue;
      ++hits;
      // The march stops once the distance is below epsilon, so it ends at most epsilon/cos short
      // of the surface along the ray, and never beyond it (the fields are exact).
      const double rounding = kFloatRelative * (glm::length(basis.origin) + t.depth);
      const double short_by = t.depth - depth;
      EXPECT_LE(short_by, scene.render.epsilon / t.cosine + rounding) << c.name << " pixel " << i << "," << j;
      EXPECT_GE(short_by, -rounding) << c.name << " pixel " << i << "," << j;
    }
  }
  EXPECT_GT(compared, w * h / 2) << "too few pixels away from silhouettes to mean anything";
  EXPECT_GT(hits, w * h / 10) << "the object should cover part of the image";
}

/// 200 spheres in a union, which render.pruning: auto evaluates from its operand grid.
const std::vector<Sphere>& union_spheres() {
  static const std::vector<Sphere> spheres = [] {
    std::vector<Sphere> out;
    unsigned state = 12345;
    const auto next = [&] {
      state = state * 1664525u + 1013904223u;
      return (state >> 8) / 16777216.0;
    };
    for (int i = 0; i < 200; ++i) out.push_back({{2 * next() - 1, 2 * next() - 1, 2 * next() - 1}, 0.1 + 0.1 * next()});
    return out;
  }();
  return spheres;
}

std::string sphere_union_yaml() {
  std::string yaml = "camera: {position: [0.3, 0.6, 2.2], look_at: [0, 0, 0]}\nsdf:\n  union:\n";
  for (const Sphere& s : union_spheres()) {
    yaml += fmt::format("    - sphere: {{center: [{:.17g}, {:.17g}, {:.17g}], radius: {:.17g}}}\n", s.center.x,
                        s.center.y, s.center.z, s.radius);
  }
  return yaml;
}

/// The nearest hit over the spheres of union_spheres.
std::optional<double> intersect_union(const glm::dvec3& o, const glm::dvec3& d) {
  std::optional<double> best;
  for (const Sphere& s : union_spheres()) {
    const std::optional<double> t = intersect_sphere(o, d, s);
    if (t && (!best || *t < *best)) best = t;
  }
  return best;
}

/// The sphere of union_spheres whose surface is nearest to p.
int nearest_sphere(const glm::dvec3& p) {
  const auto gap = [&](const Sphere& s) { return std::abs(glm::length(p - s.center) - s.radius); };
  int nearest = 0;
  for (std::size_t i = 1; i < union_spheres().size(); ++i) {
    if (gap(union_spheres()[i]) < gap(union_spheres()[static_cast<std::size_t>(nearest)]))
      nearest = static_cast<int>(i);
  }
  return nearest;
}

const std::vector<DepthCase>& depth_cases() {
  static const std::vector<DepthCase> cases = {
      {"sphere_union_by_operand_grid", sphere_union_yaml(),
       [](const glm::dvec3& o, const glm::dvec3& d) { return intersect_union(o, d); },
       [](const glm::dvec3& p) { return glm::normalize(p - union_spheres()[nearest_sphere(p)].center); },
       [](const glm::dvec3& p) { return nearest_sphere(p); }},
      {"sphere",
       "camera: {position: [0.3, 0.5, 4], look_at: [0, 0, 0]}\nsdf: {sphere: {center: [0, 0, 0], radius: 1}}\n",
       [](const glm::dvec3& o, const glm::dvec3& d) {
         return intersect_sphere(o, d, Sphere{{0, 0, 0}, 1.0});
       },
       [](const glm::dvec3& p) { return glm::normalize(p); },
       {}},
      {"box",
       "camera: {position: [-2, 3, 4], look_at: [0, 0, 0]}\nsdf: {box: {center: [0.2, 0, 0], half_size: [1, 0.5, "
       "0.75]}}\n",
       [](const glm::dvec3& o, const glm::dvec3& d) {
         return intersect_box(o, d, Box{{0.2, 0, 0}, {1, 0.5, 0.75}});
       },
       [](const glm::dvec3& p) {
         const glm::dvec3 q = (p - glm::dvec3(0.2, 0, 0)) / glm::dvec3(1, 0.5, 0.75);
         const glm::dvec3 a = glm::abs(q);
         if (a.x >= a.y && a.x >= a.z) return glm::dvec3(q.x > 0 ? 1 : -1, 0, 0);
         if (a.y >= a.z) return glm::dvec3(0, q.y > 0 ? 1 : -1, 0);
         return glm::dvec3(0, 0, q.z > 0 ? 1 : -1);
       },
       {}},
      {"plane",
       "camera: {position: [-2, 4, 4], look_at: [0, 0, 0]}\nsdf: {plane: {normal: [0, 1, 0], offset: 1}}\n",
       [](const glm::dvec3& o, const glm::dvec3& d) {
         return intersect_plane(o, d, Plane{{0, 1, 0}, 1.0});
       },
       [](const glm::dvec3&) { return glm::dvec3(0, 1, 0); },
       {}},
  };
  return cases;
}

void PrintTo(const DepthCase& c, std::ostream* os) { *os << c.name; }

class ExactDepth : public ::testing::TestWithParam<DepthCase> {};

TEST_P(ExactDepth, MatchesClosedFormAtEveryPacketWidth) {
  for (int lanes : {1, 4, 8, 16}) check_exact_depth(GetParam(), lanes);
}

TEST_P(ExactDepth, HoldsWithATighterEpsilon) {
  DepthCase c = GetParam();
  c.scene_yaml += "render: {epsilon: 1.0e-5, max_steps: 1000}\n";
  check_exact_depth(c, 16);
}

// The id channel away from silhouettes: the number of the object the closed form hits (the
// spheres' order in the file; the union's from its operand grid), -1 on a miss; the reference's too.
TEST_P(ExactDepth, IdsAreThePrimitivesHit) {
  const DepthCase& c = GetParam();
  Scene scene = scene_from_yaml(c.scene_yaml);
  scene.render.width = 96;
  scene.render.height = 64;
  OpenClOptions options;
  options.purpose = KernelPurpose::Normals;
  const FrameBuffers device = render_opencl(scene, options).buffers;
  const FrameBuffers reference = render_reference(scene);
  const std::vector<PixelTruth> truth = pixel_truths(c, scene);
  const int w = scene.render.width, h = scene.render.height;
  std::set<float> seen;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      if (near_silhouette(truth, w, h, i, j)) continue;
      const PixelTruth& t = truth[static_cast<std::size_t>(j) * w + i];
      const float want = t.hit ? static_cast<float>(t.object) : kMissId;
      ASSERT_EQ(device.at(Channel::Id, i, j), want) << c.name << " pixel " << i << "," << j;
      ASSERT_EQ(reference.at(Channel::Id, i, j), want) << c.name << " pixel " << i << "," << j;
      seen.insert(want);
    }
  }
  EXPECT_GE(seen.size(), c.object_at ? 20u : 1u) << c.name << ": the image should show many of its objects";
}

INSTANTIATE_TEST_SUITE_P(Primitives, ExactDepth, ::testing::ValuesIn(depth_cases()),
                         [](const auto& info) { return info.param.name; });

/// A pixel where the normals program hit a sphere: its depth, and the distance of its normal from
/// the closed form normalize(p - centre) at the point p where the march stopped.
struct SphereNormalError {
  int i = 0, j = 0;
  double depth = 0.0, error = 0.0;
};

std::vector<SphereNormalError> sphere_normal_errors(const Scene& scene, int lanes, const glm::dvec3& centre) {
  OpenClOptions options;
  options.lanes = lanes;
  options.purpose = KernelPurpose::Normals;
  const FrameBuffers buffers = render_opencl(scene, options).buffers;
  const CameraBasis basis = camera_basis(scene.camera, scene.render.width, scene.render.height);
  std::vector<SphereNormalError> hits;
  for (int j = 0; j < scene.render.height; ++j) {
    for (int i = 0; i < scene.render.width; ++i) {
      const double depth = buffers.at(Channel::Depth, i, j);
      if (!std::isfinite(depth)) continue;
      const glm::dvec3 p = basis.origin + depth * pixel_ray_direction(basis, i, j);
      const glm::dvec3 normal(buffers.at(Channel::NX, i, j), buffers.at(Channel::NY, i, j),
                              buffers.at(Channel::NZ, i, j));
      hits.push_back({i, j, depth, glm::length(normal - glm::normalize(p - centre))});
    }
  }
  return hits;
}

// The kernel's normals against the sphere's closed form, normalize(p) at the point p where the
// march stopped (the gradient of the exact field there), for each finite-difference method: the
// central stencil errs by ~(h kappa)^2, the one-sided ones (tetrahedral, forward) by ~h kappa with
// kappa = 1 here; twice that, plus the float rounding of the taps' difference over h.
TEST(KernelNormals, MatchTheSphereClosedFormForEachMethod) {
  for (const char* method : {"central", "tetrahedral", "forward"}) {
    Scene scene =
        scene_from_yaml(fmt::format("camera: {{position: [0.3, 0.5, 4], look_at: [0, 0, 0]}}\n"
                                    "render: {{width: 64, height: 48, normal_method: {}, normal_epsilon: 1.0e-3}}\n"
                                    "sdf: {{sphere: {{radius: 1}}}}\n",
                                    method));
    const double camera_distance = glm::length(scene.camera.position);
    const double h = scene.render.normal_epsilon;
    const double stencil = std::string(method) == "central" ? 2.0 * h * h : 2.0 * h;
    for (int lanes : {1, 16}) {
      const std::vector<SphereNormalError> hits = sphere_normal_errors(scene, lanes, glm::dvec3(0.0));
      for (const SphereNormalError& hit : hits) {
        const double rounding = 2.0 * std::sqrt(3.0) * kFloatRelative * (camera_distance + hit.depth) / h;
        EXPECT_LE(hit.error, stencil + rounding) << method << " lanes " << lanes << " pixel " << hit.i << "," << hit.j;
      }
      EXPECT_GT(hits.size(), 300u) << method << ": the sphere covers part of the image";
    }
  }
}

// Far from the map frame's origin (the camera at the origin, the sphere 58 away along x, so the
// hits have x of 57 to 58, where float's spacing is 3.8e-6, and y, z near 0), each axis's taps
// p +- h round to float: x's spacing differs from 2h by a fraction of a unit of the last place there
// (0.8 % at h = 1e-4), y's and z's hardly, so a normal divided by 2h on every axis turned by 0.27
// degrees (issue 26). Divided by the taps' actual spacing, what is left is the rounding of the tap
// values: each is |q| - r with q = tap - c exact or nearly (Sterbenz on x) and |q| close to r, two
// roundings of about u r; a difference of two taps over the spacing 2h errs by at most 2 u r / h
// per component, 2 sqrt(3) u r / h in all (0.12 degrees; measured 0.04), against which the central
// stencil's 2 h^2 is nothing.
TEST(KernelNormals, HoldFarFromTheFrameOrigin) {
  const double r = 1.0, h = 1e-4;
  Scene scene =
      scene_from_yaml(fmt::format("camera: {{position: [0, 0, 0], look_at: [58, 0, 0.5], fov: 3}}\n"
                                  "render: {{width: 48, height: 48, normal_epsilon: {}, max_distance: 100}}\n"
                                  "sdf: {{sphere: {{center: [58, 0, 0.5], radius: {}}}}}\n",
                                  h, r));
  ASSERT_EQ(map_frame_origin(scene), glm::dvec3(0.0));
  const double u = 0x1p-24;  // float's unit roundoff
  const double tolerance = 2.0 * h * h + 2.0 * std::sqrt(3.0) * u * r / h;
  for (int lanes : {1, 16}) {
    const std::vector<SphereNormalError> hits = sphere_normal_errors(scene, lanes, glm::dvec3(58.0, 0.0, 0.5));
    double largest = 0.0;
    for (const SphereNormalError& hit : hits) largest = std::max(largest, hit.error);
    EXPECT_LE(largest, tolerance) << "lanes " << lanes << ": " << glm::degrees(largest) << " degrees";
    EXPECT_GT(hits.size(), 48u * 48u / 4u) << "the sphere covers part of the image";
  }
}

}  // namespace
}  // namespace clmarch
