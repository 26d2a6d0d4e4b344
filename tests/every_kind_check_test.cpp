// Every node kind of scene/node_kinds.def, rendered and passed through the check against the double
// reference far from the origin, in float and double (issue 25): the scene of each kind is
// written from its declaration, so a kind added to the list is covered without editing this file.
#include "check/cross_check.hpp"
#include "reference/reference_renderer.hpp"
#include "scene/scene_bounds.hpp"
#include "stress_support.hpp"
#include "support/kind_scenes.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <string>
#include <type_traits>

namespace clmarch {
namespace {

using testing::kind_node;
using testing::kind_render_settings;

class EveryKind : public ::testing::TestWithParam<NodeKind> {};

TEST_P(EveryKind, PassesTheCheckFarFromTheOrigin) {
  const NodeKind kind = GetParam();
  // Aimed at the centre of the kind's bounding sphere from 2.6 radii (the sphere fills the 50 degree
  // view), or at its origin from 8 where it has none (planes, terrain, infinite cylinders).
  const Node local = testing::scene_from_yaml("sdf:\n  " + kind_node(kind, glm::dvec3(0.0)) + "\n").sdf;
  const std::optional<BoundingSphere> bound = node_bounds(local);
  const glm::dvec3 target = bound ? bound->center : glm::dvec3(0.0);
  const double distance = bound ? 2.6 * bound->radius : 8.0;
  const glm::dvec3 eye = target + distance * glm::normalize(glm::dvec3(0.55, 0.45, 0.7));
  // Far from the origin only: the harder case (positions folded into the map frame), and the one
  // every kind must get right; near the origin the other suites render them.
  const glm::dvec3 offset(1500.0, -1200.0, 900.0);
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

INSTANTIATE_TEST_SUITE_P(Kinds, EveryKind, ::testing::ValuesIn(kAllNodeKinds),
                         [](const auto& info) { return std::string(node_kind_name(info.param)); });

}  // namespace
}  // namespace clmarch
