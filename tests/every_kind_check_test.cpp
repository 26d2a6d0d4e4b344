// Every node kind of scene/node_kinds.def, rendered and passed through the check against the double
// reference at the origin and far from it, in float and double (issue 25): the scene of each kind is
// written from its declaration, so a kind added to the list is covered without editing this file.
#include "check/cross_check.hpp"
#include "reference/reference_renderer.hpp"
#include "scene/scene_bounds.hpp"
#include "stress_support.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <string>
#include <type_traits>

namespace clmarch {
namespace {

/// A value for a required parameter, from its kind of value and range: what a scene would give.
std::string required_value(const ParamSpec& spec, int integer_vectors_before) {
  switch (spec.type) {
    case ParamType::Scalar:
      // A twist's or bend's rate, in degrees a unit, wants more than 0.15.
      if (spec.range.contains(30.0) && spec.range.contains(-30.0)) return "30";
      if (spec.range.contains(0.15)) return "0.15";
      break;
    case ParamType::Integer: return spec.range.contains(3.0) ? "3" : fmt::format("{}", spec.range.low);
    case ParamType::Vector: return spec.range.contains(0.0) ? "[1.2, 0, 0]" : "[1.2, 0.8, 1]";
    // min before max, as repeat_limited declares them.
    case ParamType::IntegerVector: return integer_vectors_before == 0 ? "[-1, 0, 0]" : "[1, 0, 0]";
    case ParamType::Axes: return "[x, z]";
    case ParamType::Point:
    case ParamType::Direction:
    case ParamType::Choice:
    case ParamType::Vector4: break;
  }
  throw std::logic_error(fmt::format("no value for a required parameter {}", spec.key));
}

/// Settings for kinds whose defaults the float render cannot follow closely enough to compare:
/// the Mandelbox's orbit at scale 2 multiplies float's rounding by up to 8 an iteration
/// (CheckFeatures.TheMandelboxAndTheJuliaSet compares scale 2 at 6 iterations). At scale -1.5 its
/// faces are dust finer than a pixel, which rays at a fixed epsilon pass through or not by
/// rounding; the pixel cone stops them at the dust's pixel-sized envelope.
std::string kind_settings(NodeKind kind) { return kind == NodeKind::Mandelbox ? "scale: -1.5, " : ""; }
std::string kind_render_settings(NodeKind kind) { return kind == NodeKind::Mandelbox ? "hit_threshold: pixel_cone, " : ""; }

/// The node of the kind, its positions moved by offset: a primitive's points, or the translate of
/// a primitive without points and of an operator (whose children stay in its frame: repetition
/// is about the frame's origin).
std::string kind_node(NodeKind kind, const glm::dvec3& offset) {
  const std::string name(node_kind_name(kind));
  std::string params = kind_settings(kind);
  bool has_points = false;
  int integer_vectors = 0;
  for (const ParamSpec& spec : param_table(kind)) {
    if (!spec.required) continue;
    params += fmt::format("{}: {}, ", spec.key, required_value(spec, integer_vectors));
    if (spec.type == ParamType::IntegerVector) ++integer_vectors;
  }
  if (is_primitive(kind)) {
    const Scene local = testing::scene_from_yaml(fmt::format("sdf:\n  {}: {{{}}}\n", name, params));
    std::visit([&](const auto& values) {
      for_each_param(values, [&](const ParamSpec& spec, const auto& value) {
        if constexpr (std::is_same_v<std::decay_t<decltype(value)>, glm::dvec3>) {
          if (spec.type != ParamType::Point) return;
          const glm::dvec3 moved = value + offset;
          params += fmt::format("{}: [{}, {}, {}], ", spec.key, moved.x, moved.y, moved.z);
          has_points = true;
        }
      });
    }, local.sdf.params);
  } else {
    const std::string children = max_children(kind) == 1
                                     ? "[{box: {half_size: [0.45, 0.35, 0.4]}}]"
                                     : "[{sphere: {center: [-0.35, 0, 0], radius: 0.6}}, "
                                       "{box: {center: [0.35, 0.15, 0.1], half_size: [0.45, 0.45, 0.45]}}]";
    params += "children: " + children + ", ";
  }
  if (!has_points) params += fmt::format("translate: [{}, {}, {}], ", offset.x, offset.y, offset.z);
  return fmt::format("{}: {{{}}}", name, params.substr(0, params.size() - 2));
}

class EveryKind : public ::testing::TestWithParam<NodeKind> {};

TEST_P(EveryKind, PassesTheCheckNearAndFar) {
  const NodeKind kind = GetParam();
  // Aimed at the centre of the kind's bounding sphere from 2.6 radii (the sphere fills the 50 degree
  // view), or at its origin from 8 where it has none (planes, terrain, infinite cylinders).
  const Node local = testing::scene_from_yaml("sdf:\n  " + kind_node(kind, glm::dvec3(0.0)) + "\n").sdf;
  const std::optional<BoundingSphere> bound = node_bounds(local);
  const glm::dvec3 target = bound ? bound->center : glm::dvec3(0.0);
  const double distance = bound ? 2.6 * bound->radius : 8.0;
  const glm::dvec3 eye = target + distance * glm::normalize(glm::dvec3(0.55, 0.45, 0.7));
  for (const glm::dvec3& offset : {glm::dvec3(0.0), glm::dvec3(1500.0, -1200.0, 900.0)}) {
    for (const char* precision : {"float", "double"}) {
      const std::string sdf = kind_node(kind, offset);
      SCOPED_TRACE(fmt::format("{}, {}", sdf, precision));
      const Scene scene = testing::scene_from_yaml(fmt::format(
          "camera: {{position: [{}, {}, {}], look_at: [{}, {}, {}], fov: 50}}\n"
          "render: {{{}width: 64, height: 36, epsilon: 1.0e-4, max_steps: 600, max_distance: {}, precision: {}}}\n"
          "sdf:\n  {}\n"
          "lights: [{{directional: {{direction: [1, 2, 1.5]}}}}]\n",
          eye.x + offset.x, eye.y + offset.y, eye.z + offset.z, target.x + offset.x, target.y + offset.y,
          target.z + offset.z, kind_render_settings(kind), 4.0 * distance + 10.0, precision, sdf));
      const FrameBuffers opencl = stress::render_checked(scene, KernelPurpose::Shaded);
      const CheckReport report = cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
      EXPECT_TRUE(report.passed()) << report.to_text();
      // Something of it is in view (the sparse Sierpinski tetrahedron covers 127 pixels, an infinite
      // cylinder seen from 8 174), enough for the check's statistics.
      EXPECT_GT(report.both_hit, 100);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, EveryKind, ::testing::ValuesIn(kAllNodeKinds),
                         [](const auto& info) { return std::string(node_kind_name(info.param)); });

}  // namespace
}  // namespace clmarch
