// Where float breaks when the camera (and the scene it looks at) is far from the origin, with and
// without tiling (issue 7). Without tiling the march runs in the map frame near the camera (its
// origin folded into the generated code in double), the cells tiling in the camera's cell (offset
// computed in double): neither depends on the offset; the mod tiling wraps world positions. CLMARCH_STRESS_SWEEP=1
// prints the whole table of docs/accuracy.md (every power of ten from 1e3 to 1e7 on each axis).
#include "analytic_intersections.hpp"
#include "check/cross_check.hpp"
#include "codegen/sdf_codegen.hpp"
#include "reference/reference_renderer.hpp"
#include "scene/camera_model.hpp"
#include "scene/tiling_model.hpp"
#include "stress_support.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>

namespace clmarch {
namespace {

using namespace stress;

constexpr int kFarImageWidth = 48;
constexpr int kFarImageHeight = 32;
constexpr double kEpsilon = 1e-4;

// A unit sphere on a floor one unit below its centre, both at `centre`, seen from 4 units away.
std::string plain_yaml(const glm::dvec3& centre) {
  return fmt::format(
      "camera: {{position: [{}, {}, {}], look_at: [{}, {}, {}], fov: 45}}\n"
      "render: {{width: {}, height: {}, epsilon: {}, max_steps: 1000, max_distance: 20}}\n"
      "sdf: {{union: [{{sphere: {{center: [{}, {}, {}], radius: 1}}}}, {{plane: {{normal: [0, 1, 0], offset: "
      "{}}}}}]}}\n",
      centre.x + 0.3, centre.y + 1.0, centre.z + 4.0, centre.x, centre.y, centre.z, kFarImageWidth, kFarImageHeight,
      kEpsilon, centre.x, centre.y, centre.z, 1.0 - centre.y);
}

/// How far a render of plain_yaml(centre) is from the closed-form answer.
struct FarErrors {
  int compared = 0;
  /// Pixels away from silhouettes and grazing rays where exactly one of render and truth hits.
  int mask_mismatch = 0;
  /// max |t* - t| / epsilon over pixels both hit.
  double depth_in_epsilons = 0.0;
  /// Worst pixel against docs/accuracy.md's depth tolerance, 0 <= t* - t <= eps/cos + 16u(|o| + t*).
  double over_documented = 0.0;
  /// Worst pixel against the tolerance at the origin, 0 <= t* - t <= eps/cos + 16u t* (no |o| term).
  double over_origin = 0.0;
  /// Worst pixel against the tolerance of the camera's frame: 16u(|o - map_frame_origin| + t*).
  double over_frame = 0.0;
};

/// The tolerance ratio of one pixel: <= 1 when 0 <= short_by <= eps/cos + rounding, rounding either side.
double over_tolerance(double short_by, double cosine, double rounding) {
  return std::max(short_by / (kEpsilon / cosine + rounding), -short_by / rounding);
}

FarErrors measure_plain(const glm::dvec3& centre) {
  const Scene scene = testing::scene_from_yaml(plain_yaml(centre));
  const FrameBuffers buffers = render_checked(scene, KernelPurpose::DepthSteps);
  const Sphere sphere{centre, 1.0};
  const Plane floor{{0, 1, 0}, 1.0 - centre.y};
  struct Truth {
    bool hit = false;
    int object = 0;  // 0 none, 1 the sphere, 2 the floor
    double depth = 0.0, cosine = 0.0;
  };
  std::vector<Truth> truth;
  for (int j = 0; j < kFarImageHeight; ++j) {
    for (int i = 0; i < kFarImageWidth; ++i) {
      const glm::dvec3 o = scene.camera.position, d = ray_direction(scene, i, j);
      const std::optional<double> ts = intersect_sphere(o, d, sphere), tp = intersect_plane(o, d, floor);
      Truth t;
      if (ts || tp) {
        const bool on_sphere = ts && (!tp || *ts <= *tp);
        t.depth = on_sphere ? *ts : *tp;
        t.hit = t.depth < scene.render.max_distance;
        t.object = t.hit ? (on_sphere ? 1 : 2) : 0;
        const glm::dvec3 normal = on_sphere ? glm::normalize(o + t.depth * d - centre) : glm::dvec3(0, 1, 0);
        t.cosine = std::abs(glm::dot(d, normal));
      }
      truth.push_back(t);
    }
  }
  const auto at = [&](int i, int j) -> const Truth& { return truth[static_cast<std::size_t>(j) * kFarImageWidth + i]; };
  FarErrors e;
  const double distance = glm::length(scene.camera.position);
  const double frame_distance = glm::length(scene.camera.position - map_frame_origin(scene));
  for (int j = 0; j < kFarImageHeight; ++j) {
    for (int i = 0; i < kFarImageWidth; ++i) {
      const Truth& t = at(i, j);
      bool silhouette = t.hit && t.cosine < kGrazingCosine;
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          const int ni = i + di, nj = j + dj;
          // Edges between the sphere and the floor count too: a shifted edge swaps which one a ray hits.
          if (ni >= 0 && nj >= 0 && ni < kFarImageWidth && nj < kFarImageHeight && at(ni, nj).object != t.object)
            silhouette = true;
        }
      }
      if (silhouette) continue;
      ++e.compared;
      const float depth = buffers.at(Channel::Depth, i, j);
      if (std::isfinite(depth) != t.hit) {
        ++e.mask_mismatch;
        continue;
      }
      if (!t.hit) continue;
      const double short_by = t.depth - depth;
      e.depth_in_epsilons = std::max(e.depth_in_epsilons, std::abs(short_by) / kEpsilon);
      e.over_documented =
          std::max(e.over_documented, over_tolerance(short_by, t.cosine, kFloatRelative * (distance + t.depth)));
      e.over_origin = std::max(e.over_origin, over_tolerance(short_by, t.cosine, kFloatRelative * t.depth));
      e.over_frame =
          std::max(e.over_frame, over_tolerance(short_by, t.cosine, kFloatRelative * (frame_distance + t.depth)));
    }
  }
  return e;
}

// The lattice of tests/tiling_test.cpp: cells of 1 x 1.5 x 0.75, a sphere of radius 0.3 in each.
std::string far_lattice_yaml(const glm::dvec3& position, const char* method) {
  const glm::dvec3 look_at = position + glm::dvec3(2.7, 1.3, 4.1);
  return fmt::format(
      "camera: {{position: [{}, {}, {}], look_at: [{}, {}, {}], fov: 60}}\n"
      "render: {{width: {}, height: {}, max_steps: 1000, epsilon: {}, max_distance: 30}}\n"
      "tiling: {{cell: [1, 1.5, 0.75], method: {}}}\n"
      "sdf: {{sphere: {{center: [0.5, 0.75, 0.375], radius: 0.3}}}}\n",
      position.x, position.y, position.z, look_at.x, look_at.y, look_at.z, kFarImageWidth, kFarImageHeight, kEpsilon,
      method);
}

/// Pixels of a lattice render with the camera at position that differ from the same render with
/// the camera at its offset inside its cell (near the origin, rendered with cells): hit/miss
/// flips or depths more than 1e-3 apart (tiling.md's criterion), and the largest depth difference.
struct LatticeDifference {
  int wrong = 0;
  /// Hits of the near render (a camera inside a sphere would hit everywhere at depth 0).
  int near_hits = 0;
  double max_depth_difference = 0.0;
  bool bitwise_equal = false;
};

LatticeDifference measure_lattice(const glm::dvec3& position, const char* method) {
  const glm::dvec3 near = offset_in_cell(position, glm::dvec3(1, 1.5, 0.75));
  const FrameBuffers reference =
      render(testing::scene_from_yaml(far_lattice_yaml(near, "cells")), KernelPurpose::DepthSteps);
  const Scene scene = testing::scene_from_yaml(far_lattice_yaml(position, method));
  const FrameBuffers far = render_checked(scene, KernelPurpose::DepthSteps);
  LatticeDifference diff;
  diff.bitwise_equal = reference.plane(Channel::Depth) == far.plane(Channel::Depth);
  for (std::size_t k = 0; k < far.plane(Channel::Depth).size(); ++k) {
    const float a = reference.plane(Channel::Depth)[k], b = far.plane(Channel::Depth)[k];
    diff.near_hits += std::isfinite(a) && a > 0.0f;
    if (std::isfinite(a) != std::isfinite(b)) {
      ++diff.wrong;
    } else if (std::isfinite(a)) {
      diff.max_depth_difference = std::max<double>(diff.max_depth_difference, std::abs(a - b));
      if (std::abs(a - b) > 1e-3) ++diff.wrong;
    }
  }
  return diff;
}

// Outside the cell's sphere at every offset of the tests (offsets along z shift it by 0.25 within its cell).
const glm::dvec3 kLatticeCamera(0.05, 0.1, 0.05);

const glm::dvec3 kAxes[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const char* const kAxisNames[] = {"x", "y", "z"};

// Without tiling, map() measures points from map_frame_origin, the camera rounded to a 64-unit
// grid, and the scene's positions are folded into the generated code relative to it in double
// (host/codegen/sdf_codegen.cpp). So 1e3 ... 1e7 away on every axis the image keeps the accuracy of
// a camera within 64 units of the origin: the origin's tolerance eps/cos + 16u t* plus 16u times
// the camera's distance from its frame origin (at most 32 sqrt(3)), and no pixel flips.
TEST(FarCamera, PlainMarchKeepsTheOriginsAccuracyOnEveryAxis) {
  for (double offset : {1e3, 1e5, 1e7}) {
    for (int a = 0; a < 3; ++a) {
      SCOPED_TRACE(fmt::format("{} at {}", kAxisNames[a], offset));
      const FarErrors e = measure_plain(kAxes[a] * offset);
      EXPECT_GT(e.compared, kFarImageWidth * kFarImageHeight / 2);
      EXPECT_EQ(e.mask_mismatch, 0);
      EXPECT_LE(e.over_frame, 1.0);
    }
  }
}

/// Renders the scene whose sdf (a YAML block under "sdf:", indented by two) sdf_at writes for a
/// function placing points relative to an offset, at the origin and 10^3 + 500 away (frame origin
/// 1472 on x), in float and in double (render.precision), and expects the cross-check against the
/// double reference to pass at both. The numbers are read from the values buffer (render.literals:
/// buffer), so that the near and far scenes of a kind, whose code differs only in its numbers
/// relative to the map frame, share one program: the numbers the host folds into the frame are the
/// same floats spelled or read (24 programs to compile became 14).
void expect_checks_near_and_far(
    const std::function<std::string(const std::function<std::string(double, double, double)>&, const glm::dvec3&)>&
        sdf_at) {
  for (const auto& [offset, precision] :
       {std::pair{glm::dvec3(0.0), "float"}, std::pair{glm::dvec3(1500.0, -1200.0, 900.0), "float"},
        std::pair{glm::dvec3(0.0), "double"}, std::pair{glm::dvec3(1500.0, -1200.0, 900.0), "double"}}) {
    SCOPED_TRACE(fmt::format("offset ({}, {}, {}), {}", offset.x, offset.y, offset.z, precision));
    // A copy to capture: clang 14 cannot capture a structured binding.
    const glm::dvec3 shift = offset;
    const auto at = [&](double x, double y, double z) {
      return fmt::format("[{}, {}, {}]", x + shift.x, y + shift.y, z + shift.z);
    };
    const std::string yaml = fmt::format(
        "camera: {{position: {}, look_at: {}, fov: 50}}\n"
        "render: {{width: 64, height: 36, epsilon: 1.0e-4, max_steps: 400, max_distance: 40, precision: {},\n"
        "         literals: buffer}}\n"
        "sdf:\n{}"
        "lights: [{{directional: {{direction: [1, 2, 1.5]}}}}]\n",
        at(4, 3, 6), at(0, 0.3, 0), precision, sdf_at(at, offset));
    const Scene scene = testing::scene_from_yaml(yaml);
    EXPECT_EQ(map_frame_origin(scene), glm::round(scene.camera.position / kMapFrameGrid) * kMapFrameGrid);
    const FrameBuffers opencl = render_checked(scene, KernelPurpose::Shaded);
    const CheckReport report = cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
    EXPECT_TRUE(report.passed()) << report.to_text();
    EXPECT_GT(report.both_hit, 64 * 36 / 2);
  }
}

// Every node kind folds the map frame origin its own way (centres, segment ends, the first
// translate on a path, plane offsets, repeat remainders, mirror planes and the polar axis; terrain
// and displacement add it back in float): scenes of all of them far away pass the cross-check
// against the double reference, as they do at the origin.
TEST(FarCamera, EveryNodeKindRendersInTheMapFrame) {
  expect_checks_near_and_far([](const auto& at, const glm::dvec3& offset) {
    return fmt::format(
        "  union:\n"
        "    - plane: {{normal: [0, 1, 0], offset: {}}}\n"
        "    - box: {{center: {}, half_size: [0.4, 0.4, 0.4], rotate: [20, 30, 0]}}\n"
        "    - capsule: {{a: {}, b: {}, radius: 0.2}}\n"
        "    - torus: {{center: {}, major_radius: 0.5, minor_radius: 0.15}}\n"
        "    - cylinder: {{center: {}, radius: 0.3, half_height: 0.5}}\n"
        "    - menger: {{center: {}, half_size: 0.5, iterations: 2}}\n"
        "    - sphere: {{radius: 0.4, translate: {}, rotate: [0, 45, 0]}}\n"
        "    - displace: {{amplitude: 0.05, frequency: 6, children: [{{sphere: {{center: {}, radius: 0.4}}}}]}}\n"
        "    - intersection:\n"
        "        - repeat: {{period: [1.5, 0, 1.5], children: [{{sphere: {{center: {}, radius: 0.4}}}}]}}\n"
        "        - box: {{center: {}, half_size: [3, 0.5, 0.8]}}\n",
        1.0 - offset.y, at(-1.5, 0, 0), at(-0.5, -0.5, 1), at(0.5, 0.2, 1.2), at(1.5, 0, 0), at(0, -0.4, 0),
        at(0, 0.8, -1.5), at(1.5, 0.6, -1.2), at(-1.5, 0.6, -1.2), fmt::format("[0, {}, 0]", offset.y - 0.6),
        at(0, -0.6, 2.5));
  });
  // The catalogue's kinds (issue 25): the operators placed by translate, their children in their frames.
  expect_checks_near_and_far([](const auto& at, const glm::dvec3& offset) {
    return fmt::format(
        "  union:\n"
        "    - plane: {{normal: [0, 1, 0], offset: {}}}\n"
        "    - octahedron: {{center: {}, size: 0.45}}\n"
        "    - hex_prism: {{center: {}, radius: 0.3, half_height: 0.4, rotate: [0, 20, 0]}}\n"
        "    - capped_cone: {{center: {}, half_height: 0.4, bottom_radius: 0.4, top_radius: 0.1}}\n"
        "    - ellipsoid: {{center: {}, radii: [0.5, 0.3, 0.4]}}\n"
        "    - elongate: {{h: [0.3, 0, 0], translate: {}, children: [{{box: {{half_size: [0.2, 0.2, 0.2]}}}}]}}\n"
        "    - onion: {{thickness: 0.05, translate: {}, children: [{{sphere: {{radius: 0.35}}}}]}}\n"
        "    - round: {{radius: 0.1, translate: {}, children: [{{box: {{half_size: [0.25, 0.25, 0.25]}}}}]}}\n"
        "    - mirror: {{axes: [x, z], translate: {}, children: [{{sphere: {{center: [0.3, 0, 0.3], radius: "
        "0.2}}}}]}}\n"
        "    - repeat_polar: {{count: 6, translate: {}, children: [{{sphere: {{center: [0.6, 0, 0], radius: "
        "0.2}}}}]}}\n"
        "    - repeat_limited: {{period: [0.6, 0, 0], min: [-2, 0, 0], max: [2, 0, 0], translate: {},\n"
        "                       children: [{{box: {{half_size: [0.15, 0.15, 0.15]}}}}]}}\n",
        1.0 - offset.y, at(-1.5, 0, 0), at(-0.5, -0.5, 1), at(0.5, 0.2, 1.2), at(1.5, 0, 0), at(0, -0.4, 0),
        at(0, 0.8, -1.5), at(1.5, 0.6, -1.2), at(-1.5, 0.6, -1.2), at(0, -0.2, 2.2), at(0, -0.6, -2.5));
  });
  // The later catalogue primitives; those given by points (round_cone, triangle, quad) move each
  // point, and the turned ones are placed by translate (a far centre would turn about the origin).
  expect_checks_near_and_far([](const auto& at, const glm::dvec3& offset) {
    return fmt::format(
        "  union:\n"
        "    - plane: {{normal: [0, 1, 0], offset: {}}}\n"
        "    - cone: {{center: {}, angle: 30, height: 0.8}}\n"
        "    - rounded_cylinder: {{center: {}, radius: 0.35, half_height: 0.4, edge_radius: 0.1}}\n"
        "    - round_cone: {{a: {}, b: {}, radius_a: 0.3, radius_b: 0.15}}\n"
        "    - capped_torus: {{angle: 120, major_radius: 0.35, minor_radius: 0.1, translate: {}, rotate: [-60, 0, "
        "0]}}\n"
        "    - link: {{center: {}, half_length: 0.2, major_radius: 0.25, minor_radius: 0.08}}\n",
        1.0 - offset.y, at(-1.5, 0.2, 0), at(-0.5, -0.5, 1), at(0.5, -0.6, 1.2), at(0.6, 0.1, 1.0), at(1.5, 0, 0),
        at(0, -0.4, 0));
  });
  expect_checks_near_and_far([](const auto& at, const glm::dvec3& offset) {
    return fmt::format(
        "  union:\n"
        "    - plane: {{normal: [0, 1, 0], offset: {}}}\n"
        "    - cut_sphere: {{center: {}, radius: 0.45, cut_height: -0.2}}\n"
        "    - pyramid: {{center: {}, half_width: 0.35, height: 0.7}}\n"
        "    - triangle: {{a: {}, b: {}, c: {}, thickness: 0.03}}\n"
        "    - quad: {{a: {}, b: {}, c: {}, d: {}, thickness: 0.03}}\n"
        "    - triangular_prism: {{center: {}, radius: 0.4, half_length: 0.4}}\n",
        1.0 - offset.y, at(-1.5, 0.2, 0), at(-0.5, -0.9, 1), at(0.3, -0.5, 1.2), at(0.9, -0.5, 1.0), at(0.6, 0.3, 1.1),
        at(1.2, -0.6, -0.4), at(1.9, -0.6, -0.4), at(1.9, 0.1, -0.2), at(1.2, 0.1, -0.2), at(0, -0.4, 0));
  });
  expect_checks_near_and_far([](const auto& at, const glm::dvec3& offset) {
    return fmt::format(
        "  union:\n"
        "    - plane: {{normal: [0, 1, 0], offset: {}}}\n"
        "    - solid_angle: {{center: {}, angle: 40, radius: 0.6}}\n"
        "    - cut_hollow_sphere: {{center: {}, radius: 0.4, cut_height: 0.1, thickness: 0.04}}\n"
        "    - death_star: {{radius: 0.45, carve_radius: 0.35, carve_distance: 0.4, translate: {}, rotate: [0, -40, "
        "0]}}\n"
        "    - rhombus: {{center: {}, half_width: 0.5, half_depth: 0.3, half_height: 0.1, corner_radius: 0.05}}\n",
        1.0 - offset.y, at(-1.5, -0.6, 0), at(-0.5, -0.4, 1), at(0.6, 0.1, 1.0), at(1.5, -0.7, -0.3));
  });
  // The blends: a sphere and a box, the first ones by their centres, the others under a translate;
  // the estimates with step_factor 0.7 (they are up to sqrt 2 steeper than the distance).
  expect_checks_near_and_far([](const auto& at, const glm::dvec3& offset) {
    const std::pair<const char*, const char*> blends[] = {
        {"union_chamfer", "radius: 0.1, step_factor: 0.7"},
        {"intersection_chamfer", "radius: 0.1, step_factor: 0.7"},
        {"difference_chamfer", "radius: 0.1, step_factor: 0.7"},
        {"union_round", "radius: 0.1, step_factor: 0.7"},
        {"intersection_round", "radius: 0.1, step_factor: 0.7"},
        {"difference_round", "radius: 0.1, step_factor: 0.7"},
        {"union_stairs", "radius: 0.15, steps: 3"},
        {"intersection_stairs", "radius: 0.15, steps: 3"},
        {"difference_stairs", "radius: 0.15, steps: 3"},
        {"union_columns", "radius: 0.15, steps: 2, step_factor: 0.7"},
        {"intersection_columns", "radius: 0.15, steps: 2, step_factor: 0.7"},
        {"difference_columns", "radius: 0.15, steps: 2, step_factor: 0.7"},
        {"xor", ""},
        {"pipe", "radius: 0.05, step_factor: 0.7"},
        {"engrave", "radius: 0.08, step_factor: 0.7"},
        {"groove", "ra: 0.08, rb: 0.05"},
        {"tongue", "ra: 0.08, rb: 0.05"}};
    std::string sdf = fmt::format("  union:\n    - plane: {{normal: [0, 1, 0], offset: {}}}\n", 1.0 - offset.y);
    int i = 0;
    for (const auto& [name, params] : blends) {
      const double x = -2.0 + 0.8 * (i % 6), z = -1.6 + 1.2 * (i / 6);
      const std::string head = fmt::format("{}{}", params, *params ? ", " : "");
      if (i < 6) {
        sdf += fmt::format(
            "    - {}: {{{}children: [{{sphere: {{center: {}, radius: 0.3}}}}, "
            "{{box: {{center: {}, half_size: [0.2, 0.2, 0.2]}}}}]}}\n",
            name, head, at(x - 0.1, 0, z), at(x + 0.15, 0.1, z));
      } else {
        sdf += fmt::format(
            "    - {}: {{{}translate: {}, children: [{{sphere: {{center: [-0.1, 0, 0], radius: 0.3}}}}, "
            "{{box: {{center: [0.15, 0.1, 0], half_size: [0.2, 0.2, 0.2]}}}}]}}\n",
            name, head, at(x, 0, z));
      }
      ++i;
    }
    return sdf;
  });
}

// A model authored far from the origin and translated home (issue 26): a transformed node's
// subtree is measured from its bound's centre, the translation folded into its positions in
// double, so 10^5 and 10^6 away (on two axes) the model renders as the one authored at home: the
// same pixels hit, depths and normals within float's rounding near the origin, and the check
// passes. With the translation applied in float in the kernel (p - translate, then the centres
// 10^6 away), 5 % of the pixels were wrong and the check failed.
TEST(FarCamera, ModelAuthoredFarAndTranslatedHomeRendersAsAtHome) {
  const auto model = [](double x, double z) {
    return fmt::format(
        "camera: {{position: [0, 1, 5], look_at: [0, 0, 0], fov: 50}}\n"
        "render: {{width: 64, height: 36, epsilon: 1.0e-4, max_steps: 400, max_distance: 40}}\n"
        "sdf:\n"
        "  union:\n"
        "    translate: [{}, 0, {}]\n"
        "    children:\n"
        "      - sphere: {{center: [{}, 0, {}], radius: 1}}\n"
        "      - box: {{center: [{}, 0, {}], half_size: [0.5, 0.5, 0.5]}}\n"
        "lights: [{{directional: {{direction: [1, 2, 1.5]}}}}]\n",
        -x, -z, x, z, x + 1.5, z);
  };
  const Scene home = testing::scene_from_yaml(model(0.0, 0.0));
  const FrameBuffers at_home = render_checked(home, KernelPurpose::Shaded);
  for (const auto& [x, z] : {std::pair{1e5, 0.0}, std::pair{1e6, 1e6}}) {
    SCOPED_TRACE(fmt::format("authored at ({}, 0, {})", x, z));
    const Scene far = testing::scene_from_yaml(model(x, z));
    const FrameBuffers opencl = render_checked(far, KernelPurpose::Shaded);
    const CheckReport report = cross_check(far, opencl, render_reference(far), reshade_hits(far, opencl));
    EXPECT_TRUE(report.passed()) << report.to_text();
    // Float's rounding of the points near the origin (|p| < 8): 16 roundings of coordinates of that size.
    const double rounding = 16.0 * 0x1p-24 * 8.0;
    int both_hit = 0;
    for (int j = 0; j < opencl.height; ++j) {
      for (int i = 0; i < opencl.width; ++i) {
        const float t = opencl.at(Channel::Depth, i, j), t_home = at_home.at(Channel::Depth, i, j);
        ASSERT_EQ(std::isfinite(t), std::isfinite(t_home)) << i << ", " << j;
        if (!std::isfinite(t)) continue;
        ++both_hit;
        EXPECT_NEAR(t, t_home, rounding) << i << ", " << j;
        const glm::dvec3 n(opencl.at(Channel::NX, i, j), opencl.at(Channel::NY, i, j), opencl.at(Channel::NZ, i, j));
        const glm::dvec3 n_home(at_home.at(Channel::NX, i, j), at_home.at(Channel::NY, i, j),
                                at_home.at(Channel::NZ, i, j));
        // Normals of points at most `rounding` apart, from taps h = render.normal_epsilon apart.
        EXPECT_LE(std::acos(std::clamp(glm::dot(n, n_home), -1.0, 1.0)), std::sqrt(3.0) * 2.0 * rounding / 1e-3)
            << i << ", " << j;
      }
    }
    EXPECT_GT(both_hit, 64 * 36 / 10);
  }
}

// The displacement texture is a function of the absolute point, whose phase f * offset the host
// reduces mod 2 pi in double (issue 26), so a displaced sphere that fills the image passes the
// cross-check with the tolerance of the map frame 10^3 + 500 away (in the scene above it is too
// small for a texture taken in the frame to show) and 10^5 away, where float's spacing of the
// absolute point is 0.008: with the phase taken in float (the absolute point added back in the
// kernel) its texture turned the normals by tens of degrees and the check failed.
TEST(FarCamera, DisplacementFarAwayKeepsTheFramesPrecision) {
  for (const glm::dvec3 centre : {glm::dvec3(1500.0, -1200.0, 900.0), glm::dvec3(1e5, -1e5, 1e5)}) {
    SCOPED_TRACE(fmt::format("sphere at ({}, {}, {})", centre.x, centre.y, centre.z));
    const Scene scene = testing::scene_from_yaml(
        fmt::format("camera: {{position: [{0}, {1}, {3}], look_at: [{0}, {1}, {2}], fov: 50}}\n"
                    "render: {{width: 64, height: 36, epsilon: 1.0e-4, max_steps: 400, max_distance: 40}}\n"
                    "sdf: {{displace: {{amplitude: 0.2, frequency: 3, children: [{{sphere: {{center: [{0}, {1}, {2}], "
                    "radius: 1}}}}]}}}}\n"
                    "lights: [{{directional: {{direction: [1, 2, 1.5]}}}}]\n",
                    centre.x, centre.y, centre.z, centre.z + 2.2));
    ASSERT_NE(map_frame_origin(scene), glm::dvec3(0.0));
    const FrameBuffers opencl = render_checked(scene, KernelPurpose::Shaded);
    const CheckReport report = cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
    EXPECT_TRUE(report.passed()) << report.to_text();
    EXPECT_GT(report.both_hit, 64 * 36 / 2);
  }
}

// Terrain noise hashes absolute lattice points; far from the origin each octave's lattice point of
// the frame origin is split on the host in double into whole cells and a fraction (issue 26), so
// 10^5 away every noise passes the check with the tolerance of the map frame. With the absolute
// point formed in float (the old path, still taken where the cells pass 2^24) the normals were
// 31 degrees off at 10^4 and 111 at 10^5, and the check refused the scene as beyond float's reach.
TEST(FarCamera, TerrainFarAwayKeepsTheFramesPrecision) {
  for (const char* noise : {"value", "perlin", "derivative"}) {
    SCOPED_TRACE(noise);
    const Scene scene = testing::scene_from_yaml(fmt::format(
        "camera: {{position: [100000, 2.4, -100000], look_at: [100003, 0.6, -99992], fov: 55}}\n"
        "render: {{width: 64, height: 36, max_steps: 400, epsilon: 1.0e-3, max_distance: 60, normal_epsilon: 2.0e-3}}\n"
        "sdf: {{terrain: {{height: -0.5, amplitude: 2.5, frequency: 0.25, octaves: 6, noise: {}, step_factor: 0.5}}}}\n"
        "lights: [{{directional: {{direction: [-0.6, 0.5, 0.4]}}}}]\n",
        noise));
    EXPECT_FALSE(takes_absolute_points(scene.sdf, map_frame_origin(scene)));
    const FrameBuffers opencl = render_checked(scene, KernelPurpose::Shaded);
    const CheckReport report = cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
    EXPECT_TRUE(report.passed()) << report.to_text();
    EXPECT_GT(report.both_hit, 64 * 36 / 3);
  }
}

// The check measures rounding by the coordinates the kernel computes with, those of the map frame
// near the camera (issue 26): 10^5 away its normal tolerance is that of a camera within 32 of its
// frame origin (sqrt(3) 16u (32 + t) / h = 3.5 degrees here), so normals turned by ten degrees
// fail it, where a tolerance of the world coordinates' size (16u 10^5 / h, past pi) passed any.
TEST(FarCamera, TheCheckSeesTurnedNormalsFarAway) {
  const Scene scene = testing::scene_from_yaml(plain_yaml(glm::dvec3(1e5, 0.0, 0.0)));
  const FrameBuffers opencl = render_checked(scene, KernelPurpose::Shaded);
  const FrameBuffers reference = render_reference(scene);
  const CheckReport report = cross_check(scene, opencl, reference);
  EXPECT_TRUE(report.passed()) << report.to_text();
  FrameBuffers turned = opencl;
  const double angle = 10.0 * M_PI / 180.0;
  for (int j = 0; j < turned.height; ++j) {
    for (int i = 0; i < turned.width; ++i) {
      const glm::dvec3 n(turned.at(Channel::NX, i, j), turned.at(Channel::NY, i, j), turned.at(Channel::NZ, i, j));
      if (!std::isfinite(turned.at(Channel::Depth, i, j))) continue;
      const glm::dvec3 across =
          glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
      const glm::dvec3 m = std::cos(angle) * n + std::sin(angle) * across;
      turned.at(Channel::NX, i, j) = static_cast<float>(m.x);
      turned.at(Channel::NY, i, j) = static_cast<float>(m.y);
      turned.at(Channel::NZ, i, j) = static_cast<float>(m.z);
    }
  }
  const CheckReport turned_report = cross_check(scene, turned, reference);
  EXPECT_FALSE(turned_report.passed());
  EXPECT_NE(turned_report.to_text().find("normal angle error p99"), std::string::npos) << turned_report.to_text();
}

// Under the cells tiling the kernel only ever sees the camera's offset in its cell (computed in
// double), so 1e7 away on each axis, off any cell boundary, renders the image of the camera at
// that offset near the origin: bit for bit on PoCL; asserted within float rounding of the depth,
// as the camera basis is derived from the world positions.
TEST(FarCamera, CellsTilingRendersTheNearImageAt1e7) {
  for (int a = 0; a < 3; ++a) {
    SCOPED_TRACE(kAxisNames[a]);
    const LatticeDifference d = measure_lattice(kLatticeCamera + kAxes[a] * 1e7, "cells");
    EXPECT_EQ(d.wrong, 0);
    EXPECT_GT(d.near_hits, kFarImageWidth * kFarImageHeight / 5);
    EXPECT_LE(d.max_depth_difference, kFloatRelative * 30.0) << "16u of the longest depth";
  }
}

// The sweep behind docs/accuracy.md's table. Only prints; run with CLMARCH_STRESS_SWEEP=1.
TEST(FarCamera, Sweep) {
  if (!sweep_requested()) GTEST_SKIP() << "set CLMARCH_STRESS_SWEEP=1 to measure every offset";
  std::cout << "| axis | offset | compared | plain: interior flips | plain: max |dt| / eps | plain: documented tol. | "
               "plain: origin tol. | plain: frame tol. | cells: wrong px | cells: max |dt| | mod: wrong px |\n";
  for (int a = 0; a < 3; ++a) {
    for (double offset : {1e2, 1e3, 1e4, 1e5, 1e6, 1e7}) {
      const FarErrors e = measure_plain(kAxes[a] * offset);
      const glm::dvec3 lattice_camera = kLatticeCamera + kAxes[a] * offset;
      const LatticeDifference cells = measure_lattice(lattice_camera, "cells");
      const LatticeDifference mod = measure_lattice(lattice_camera, "mod");
      std::cout << fmt::format(
          "| {} | 1e{} | {} | {} | {:.3g} | {:.3g} | {:.3g} | {:.3g} | {} | {:.2g}{} | {:.1f} % |\n", kAxisNames[a],
          std::lround(std::log10(offset)), e.compared, e.mask_mismatch, e.depth_in_epsilons, e.over_documented,
          e.over_origin, e.over_frame, cells.wrong, cells.max_depth_difference, cells.bitwise_equal ? " (bitwise)" : "",
          100.0 * mod.wrong / (kFarImageWidth * kFarImageHeight));
    }
  }
}

}  // namespace
}  // namespace clmarch
