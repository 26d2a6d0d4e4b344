// Tiling's unit-cell traversal against the exact answer: a lattice of spheres whose first hit is
// found by a 3D grid walk (Amanatides-Woo) with closed-form ray-sphere intersections in double,
// with the camera near and very far from the origin, and the rays that stress a grid walk.
#include "analytic_intersections.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/camera_model.hpp"
#include "support/test_support.hpp"
#include "support/tolerances.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>

namespace clmarch {
namespace {

// A lattice with a different cell size per axis; each cell holds one sphere well inside it.
const glm::dvec3 kCell(1.0, 1.5, 0.75);
const Sphere kCellSphere{{0.5, 0.75, 0.375}, 0.3};
using testing::kGrazingCosine;
// Float rounding in the cell's frame: the coordinates are at most a cell wide, plus the depth.
using testing::kFloatRelative;

std::string lattice_yaml(const glm::dvec3& position, const glm::dvec3& look_at, int width, int height,
                         const char* up = "[0, 1, 0]", const char* method = "cells", double radius = 0.3,
                         double centre_x = 0.5) {
  return fmt::format(
      "camera: {{position: [{}, {}, {}], look_at: [{}, {}, {}], up: {}, fov: 60}}\n"
      "render: {{width: {}, height: {}, max_steps: 1000, epsilon: 1.0e-4, max_distance: 30}}\n"
      "tiling: {{cell: [1, 1.5, 0.75], method: {}}}\n"
      "sdf: {{sphere: {{center: [{}, 0.75, 0.375], radius: {}}}}}\n",
      position.x, position.y, position.z, look_at.x, look_at.y, look_at.z, up, width, height, method, centre_x, radius);
}

struct LatticeHit {
  double depth = 0.0;
  glm::dvec3 normal{0.0};
};

/// First sphere of the lattice along the ray, by walking the cells it crosses in order.
std::optional<LatticeHit> lattice_first_hit(const glm::dvec3& o, const glm::dvec3& d, double max_distance,
                                            double radius = kCellSphere.radius,
                                            double centre_x = kCellSphere.center.x) {
  glm::dvec3 index = glm::floor(o / kCell);
  glm::dvec3 next_wall, step_t;
  for (int a = 0; a < 3; ++a) {
    step_t[a] = d[a] != 0.0 ? kCell[a] / std::abs(d[a]) : INFINITY;
    next_wall[a] = d[a] > 0.0   ? ((index[a] + 1.0) * kCell[a] - o[a]) / d[a]
                   : d[a] < 0.0 ? (index[a] * kCell[a] - o[a]) / d[a]
                                : INFINITY;
  }
  double t = 0.0;
  while (t < max_distance) {
    const Sphere sphere{index * kCell + glm::dvec3(centre_x, kCellSphere.center.y, kCellSphere.center.z), radius};
    if (const std::optional<double> hit = intersect_sphere(o, d, sphere)) {
      return LatticeHit{*hit, glm::normalize(o + *hit * d - sphere.center)};
    }
    // The sphere lies inside its cell, so a miss here means the ray leaves the cell first.
    int axis = 0;
    for (int a = 1; a < 3; ++a) {
      if (next_wall[a] < next_wall[axis]) axis = a;
    }
    t = next_wall[axis];
    next_wall[axis] += step_t[axis];
    index[axis] += d[axis] > 0.0 ? 1.0 : -1.0;
  }
  return std::nullopt;
}

FrameBuffers render_lattice(const glm::dvec3& position, const glm::dvec3& look_at, int width, int height,
                            KernelPurpose purpose = KernelPurpose::DepthSteps) {
  const Scene scene = testing::scene_from_yaml(lattice_yaml(position, look_at, width, height));
  OpenClOptions options;
  options.purpose = purpose;
  return render_opencl(scene, options).buffers;
}

void expect_lattice_depths(const glm::dvec3& position, const glm::dvec3& look_at) {
  SCOPED_TRACE(fmt::format("camera at ({}, {}, {})", position.x, position.y, position.z));
  const int w = 48, h = 32;
  const FrameBuffers buffers = render_lattice(position, look_at, w, h, KernelPurpose::Normals);
  const Scene scene = testing::scene_from_yaml(lattice_yaml(position, look_at, w, h));
  const CameraBasis basis = camera_basis(scene.camera, w, h);
  std::vector<std::optional<LatticeHit>> truth;
  std::vector<double> cosine;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const glm::dvec3 dir = pixel_ray_direction(basis, i, j);
      truth.push_back(lattice_first_hit(basis.origin, dir, scene.render.max_distance));
      cosine.push_back(truth.back() ? std::abs(glm::dot(dir, truth.back()->normal)) : 0.0);
    }
  }
  const auto hit_at = [&](int i, int j) { return truth[static_cast<std::size_t>(j) * w + i].has_value(); };
  int compared = 0, hits = 0;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      bool silhouette = hit_at(i, j) && cosine[k] < kGrazingCosine;
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          const int ni = i + di, nj = j + dj;
          if (ni >= 0 && nj >= 0 && ni < w && nj < h && hit_at(ni, nj) != hit_at(i, j)) silhouette = true;
        }
      }
      if (silhouette) continue;
      ++compared;
      const float depth = buffers.at(Channel::Depth, i, j);
      ASSERT_EQ(std::isfinite(depth), hit_at(i, j)) << "pixel " << i << "," << j;
      if (!hit_at(i, j)) continue;
      ++hits;
      const double t = truth[k]->depth;
      const double rounding = kFloatRelative * (glm::length(kCell) + t) * 4.0;
      EXPECT_LE(t - depth, scene.render.epsilon / cosine[k] + rounding) << "pixel " << i << "," << j;
      EXPECT_GE(t - depth, -rounding) << "pixel " << i << "," << j;
      // The normal comes from the hit cell's own frame.
      const glm::dvec3 n(buffers.at(Channel::NX, i, j), buffers.at(Channel::NY, i, j), buffers.at(Channel::NZ, i, j));
      EXPECT_GT(glm::dot(n, truth[k]->normal), 0.999) << "pixel " << i << "," << j;
    }
  }
  EXPECT_GT(compared, w * h / 2);
  EXPECT_GT(hits, w * h / 5);
}

const glm::dvec3 kNearCamera(0.3, 0.6, 0.1);
const glm::dvec3 kView(2.7, 1.3, 4.1);

TEST(TilingCells, MatchesTheGridWalkNearTheOrigin) { expect_lattice_depths(kNearCamera, kNearCamera + kView); }

// Whole numbers of cells away along each axis and a diagonal: the same picture, as exact as near
// the origin (the seed's world-space mod loses all precision long before 1e7).
TEST(TilingCells, MatchesTheGridWalkFarFromTheOrigin) {
  for (double distance : {1e3, 1e5, 1e7}) {
    for (const glm::dvec3& axis :
         {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1), glm::dvec3(1, -1, 1)}) {
      const glm::dvec3 shift = glm::round(axis * distance / kCell) * kCell;
      expect_lattice_depths(kNearCamera + shift, kNearCamera + shift + kView);
    }
  }
}

TEST(TilingCells, FarCameraRendersTheSameImage) {
  const FrameBuffers near = render_lattice(kNearCamera, kNearCamera + kView, 48, 32);
  const glm::dvec3 shift = glm::round(glm::dvec3(1e7, -1e7, 1e7) / kCell) * kCell;
  const FrameBuffers far = render_lattice(kNearCamera + shift, kNearCamera + shift + kView, 48, 32);
  int differing = 0;
  for (std::size_t k = 0; k < near.plane(Channel::Depth).size(); ++k) {
    const float a = near.plane(Channel::Depth)[k], b = far.plane(Channel::Depth)[k];
    if (std::isfinite(a) != std::isfinite(b) || (std::isfinite(a) && std::abs(a - b) > 1e-5f * (1.0f + a))) ++differing;
  }
  EXPECT_LE(differing, 2);
}

/// Depth and steps of the single ray of a 1x1 image, which is exactly the camera's forward axis.
struct OneRay {
  float depth;
  float steps;
  float wall_steps;
};

OneRay march_one_ray(const glm::dvec3& position, const glm::dvec3& direction, int lanes,
                     RayBounds bounds = RayBounds::Sphere) {
  const bool vertical = direction.x == 0.0 && direction.z == 0.0;
  Scene scene = testing::scene_from_yaml(
      lattice_yaml(position, position + direction, 1, 1, vertical ? "[1, 0, 0]" : "[0, 1, 0]"));
  scene.render.bounds = bounds;
  OpenClOptions options;
  options.lanes = lanes;
  options.purpose = KernelPurpose::Normals;
  const FrameBuffers b = render_opencl(scene, options).buffers;
  for (Channel c : {Channel::Steps, Channel::NX, Channel::NY, Channel::NZ}) {
    EXPECT_TRUE(std::isfinite(b.at(c, 0, 0))) << kChannelNames[static_cast<int>(c)];
  }
  EXPECT_FALSE(std::isnan(b.at(Channel::Depth, 0, 0)));
  return {b.at(Channel::Depth, 0, 0), b.at(Channel::Steps, 0, 0), b.at(Channel::WallSteps, 0, 0)};
}

struct SpecialRay {
  std::string name;
  glm::dvec3 position;
  glm::dvec3 direction;
};

void PrintTo(const SpecialRay& r, std::ostream* os) { *os << r.name; }

// Rays a grid walk can get wrong: along axes (zero direction components), starting exactly on a
// wall or a corner, running along a wall or an edge, crossing edges (two walls at once).
const std::vector<SpecialRay>& special_rays() {
  static const std::vector<SpecialRay> rays = {
      {"along_x_from_wall", {0.0, 0.75, 0.375}, {1, 0, 0}},
      {"against_x_from_wall", {0.0, 0.75, 0.375}, {-1, 0, 0}},
      {"along_z_off_centre", {0.35, 0.75, 0.0}, {0, 0, 1}},
      {"along_y_far_away", {0.5 + 4e6, 1.2, 0.375 - 3e6}, {0, -1, 0}},
      {"along_edge_from_corner", {0.0, 0.0, 0.0}, {1, 0, 0}},
      {"along_wall", {0.3, 0.0, 0.2}, {0.6, 0, 0.8}},
      {"through_edges", {0.0, 0.0, 0.0}, {1.0, 1.5, 0.0}},
      {"through_edges_off_plane", {0.0, 0.0, 0.375}, {-1.0, -1.5, 0.0}},
      {"through_corners", {0.0, 0.0, 0.0}, {-1.0, 1.5, 0.75}},
      {"from_far_corner", {1e7, -1.5e6, 7.5e5}, {0.3, 0.2, 1.0}},
  };
  return rays;
}

class TilingSpecialRays : public ::testing::TestWithParam<SpecialRay> {};

TEST_P(TilingSpecialRays, TerminateAndMatchTheGridWalk) {
  const SpecialRay& r = GetParam();
  const glm::dvec3 dir = glm::normalize(r.direction);
  const std::optional<LatticeHit> truth = lattice_first_hit(r.position, dir, 30.0);
  // With the cell content's bounding sphere (the default) and without it (distance steps alone).
  for (RayBounds bounds : {RayBounds::Sphere, RayBounds::None}) {
    for (int lanes : {1, 16}) {
      SCOPED_TRACE(fmt::format("lanes {}, bounds {}", lanes, bounds == RayBounds::Sphere ? "sphere" : "none"));
      const OneRay ray = march_one_ray(r.position, dir, lanes, bounds);
      EXPECT_LT(ray.steps, 1000.0f) << "the step budget must not run out on a " << r.name << " ray";
      EXPECT_LE(ray.wall_steps, ray.steps);
      ASSERT_EQ(std::isfinite(ray.depth), truth.has_value());
      if (truth) {
        const double bound = 1e-4 / std::max(std::abs(glm::dot(dir, truth->normal)), kGrazingCosine) + 1e-5;
        EXPECT_NEAR(ray.depth, truth->depth, bound);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Rays, TilingSpecialRays, ::testing::ValuesIn(special_rays()),
                         [](const auto& info) { return info.param.name; });

TEST(TilingCells, StepsCountWallStepsToo) {
  // Straight along x through the gaps between the spheres, without the cells' bounding sphere:
  // only wall steps and distance steps in between, and every one is counted.
  const OneRay ray = march_one_ray({0.0, 0.05, 0.05}, {1, 0, 0}, 16, RayBounds::None);
  EXPECT_TRUE(std::isinf(ray.depth));
  EXPECT_GE(ray.wall_steps, 29.0f) << "one wall per cell over max_distance 30";
  EXPECT_GT(ray.steps, ray.wall_steps);
}

TEST(TilingCells, CellsPassedByTakeOneStepEach) {
  // The same ray with the cell content's bounding sphere (render.bounds: sphere, the default):
  // it passes every sphere by, so each cell takes one step, straight to its wall.
  const OneRay ray = march_one_ray({0.0, 0.05, 0.05}, {1, 0, 0}, 16);
  EXPECT_TRUE(std::isinf(ray.depth));
  EXPECT_GE(ray.wall_steps, 29.0f) << "one wall per cell over max_distance 30";
  EXPECT_EQ(ray.steps, ray.wall_steps);
}

/// Share of pixels whose depth is wrong (hit/miss differs from the grid walk, or off by more than
/// 1e-3) for a lattice render with this method, sphere and camera.
double wrong_pixel_share(const char* method, double radius, double centre_x, const glm::dvec3& camera) {
  const int w = 64, h = 40;
  const Scene scene =
      testing::scene_from_yaml(lattice_yaml(camera, camera + kView, w, h, "[0, 1, 0]", method, radius, centre_x));
  OpenClOptions options;
  options.purpose = KernelPurpose::DepthSteps;
  const FrameBuffers b = render_opencl(scene, options).buffers;
  const CameraBasis basis = camera_basis(scene.camera, w, h);
  int wrong = 0;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const std::optional<LatticeHit> truth = lattice_first_hit(basis.origin, pixel_ray_direction(basis, i, j),
                                                                scene.render.max_distance, radius, centre_x);
      const float depth = b.at(Channel::Depth, i, j);
      if (std::isfinite(depth) != truth.has_value() || (truth && std::abs(depth - truth->depth) > 1e-3)) ++wrong;
    }
  }
  return static_cast<double>(wrong) / (w * h);
}

// The comparison docs/tiling.md reports: mod holds for an object small against its cell and
// central in it, near the origin; it breaks once the object is large or off-centre (the copy in
// the next cell is nearer than the one the wrapped point measures, so steps overshoot into it)
// and once the camera is far from the origin (float positions); cells holds everywhere. Numbers
// are printed for the document.
TEST(TilingMethods, ModBreaksWhereTheArticleSaysAndCellsHolds) {
  const glm::dvec3 far = kNearCamera + glm::round(glm::dvec3(1e5, 0, 0) / kCell) * kCell;
  const struct {
    const char* label;
    double radius;
    double centre_x;
    glm::dvec3 camera;
    bool mod_holds;
  } cases[] = {{"centred sphere r 0.15, near the origin", 0.15, 0.5, kNearCamera, true},
               {"sphere r 0.15 off-centre (x 0.3), near the origin", 0.15, 0.3, kNearCamera, false},
               {"sphere r 0.28 off-centre (x 0.35), near the origin", 0.28, 0.35, kNearCamera, false},
               {"centred sphere r 0.15, camera 1e5 from the origin", 0.15, 0.5, far, false}};
  for (const auto& c : cases) {
    const double mod = wrong_pixel_share("mod", c.radius, c.centre_x, c.camera);
    const double cells = wrong_pixel_share("cells", c.radius, c.centre_x, c.camera);
    std::printf("tiling comparison, %s: wrong pixels mod %.1f%%, cells %.1f%%\n", c.label, 100 * mod, 100 * cells);
    EXPECT_LT(cells, 0.02) << c.label;
    if (c.mod_holds) {
      EXPECT_LT(mod, 0.02) << c.label;
    } else {
      EXPECT_GT(mod, 0.03) << c.label << ": mod was expected to break here";
    }
  }
}

// The material of a hit under the mod tiling comes from the hit point wrapped into its cell (the
// march wraps it before map_color): a cell of a red and a blue sphere, both centred well inside
// on y and z, shows each pixel the same color under mod and under cells wherever both hit at the
// same depth, in every cell the rays cross, not only the one at the origin.
TEST(TilingMethods, ModAndCellsAgreeOnTheMaterialInEveryCell) {
  const auto yaml = [](const char* method) {
    return fmt::format(
        "camera: {{position: [0.3, 0.6, 0.1], look_at: [3.0, 1.9, 4.2], fov: 60}}\n"
        "render: {{width: 64, height: 48, max_steps: 1000, epsilon: 1.0e-4, max_distance: 30}}\n"
        "tiling: {{cell: [1, 1.5, 0.75], method: {}}}\n"
        "sdf:\n  union:\n"
        "    - sphere: {{center: [0.3, 0.75, 0.375], radius: 0.15, color: [1, 0, 0]}}\n"
        "    - sphere: {{center: [0.7, 0.75, 0.375], radius: 0.15, color: [0, 0, 1]}}\n"
        "lights: [{{directional: {{direction: [0.3, 1, 0.2]}}}}]\n",
        method);
  };
  OpenClOptions options;
  options.purpose = KernelPurpose::Shaded;
  const FrameBuffers mod = render_opencl(testing::scene_from_yaml(yaml("mod")), options).buffers;
  const FrameBuffers cells = render_opencl(testing::scene_from_yaml(yaml("cells")), options).buffers;
  int compared = 0, differing = 0;
  for (int j = 0; j < 48; ++j) {
    for (int i = 0; i < 64; ++i) {
      const float a = mod.at(Channel::Depth, i, j), b = cells.at(Channel::Depth, i, j);
      if (!std::isfinite(a) || !std::isfinite(b) || std::abs(a - b) > 1e-3f * (1.0f + b)) continue;
      ++compared;
      const float dr = std::abs(mod.at(Channel::R, i, j) - cells.at(Channel::R, i, j));
      const float db = std::abs(mod.at(Channel::B, i, j) - cells.at(Channel::B, i, j));
      if (std::max(dr, db) > 0.02f) ++differing;
    }
  }
  EXPECT_GT(compared, 64 * 48 / 10);
  EXPECT_LE(differing, compared / 100) << differing << " of " << compared << " pixels differ in color";
}

}  // namespace
}  // namespace clmarch
