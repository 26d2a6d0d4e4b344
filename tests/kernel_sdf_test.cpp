// Every primitive, operator and transform against closed-form distances, evaluated both by the
// generated OpenCL map() on the device (at every packet width) and by the CPU reference.
#include "prune/operand_grid.hpp"
#include "reference/reference_sdf.hpp"
#include "render/opencl_renderer.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

namespace clmarch {
namespace {

using testing::scene_from_yaml;

// The points have |p| <= 20 and the formulas a handful of float operations: a few float ulps there.
constexpr double kKernelTolerance = 2e-5;
// The reference is double precision: rounding only.
constexpr double kReferenceTolerance = 1e-12;

struct PointCase {
  glm::dvec3 point;
  double expected;
};

struct SdfCase {
  std::string name;
  std::string sdf_yaml;
  std::vector<PointCase> points;
};

const double kSqrt2 = std::sqrt(2.0);
const double kSqrt3 = std::sqrt(3.0);
// The radius of two columns across r = 1: 1 / (2 + 2 sqrt 2).
const double kColumn2 = 0.5 / (1.0 + kSqrt2);

// Symmetric shapes are probed on both sides of each symmetry plane: a dropped fabs() shows only there.
const std::vector<SdfCase>& sdf_cases() {
  static const std::vector<SdfCase> cases = {
      {"sphere", "sphere: {center: [1, 2, 3], radius: 0.5}", {{{1, 2, 5}, 1.5}, {{1, 2, 3}, -0.5}, {{4, 6, 3}, 4.5}}},
      {"box",
       "box: {center: [0, 0, 0], half_size: [1, 2, 3]}",
       {{{3, 0, 0}, 2.0}, {{2, 3, 4}, kSqrt3}, {{-2, -3, -4}, kSqrt3}, {{0.5, 0, 0}, -0.5}, {{0, 0, 0}, -1.0}}},
      {"round_box",
       "round_box: {half_size: [1, 1, 1], radius: 0.25}",
       {{{2, 0, 0}, 1.0}, {{2, 2, 2}, kSqrt3 * 1.25 - 0.25}, {{-2, -2, -2}, kSqrt3 * 1.25 - 0.25}, {{0, 0, 0}, -1.0}}},
      // Bars are 2 * thickness wide, flush with the faces: x, y in [0.8, 1] for the bar along z.
      {"box_frame",
       "box_frame: {half_size: [1, 1, 1], thickness: 0.1}",
       {{{0.9, 0.9, 0}, -0.1},
        {{-0.9, -0.9, 0}, -0.1},
        {{0, 0, 0}, 0.8 * kSqrt2},
        {{2, 1, 0}, 1.0},
        {{-2, -1, 0}, 1.0}}},
      {"torus",
       "torus: {major_radius: 1, minor_radius: 0.25}",
       {{{0, 0, 0}, 0.75},
        {{1, 0, 0}, -0.25},
        {{-1, 0, 0}, -0.25},
        {{0, 2, 0}, std::sqrt(5.0) - 0.25},
        {{0, -2, 0}, std::sqrt(5.0) - 0.25},
        {{0, 0, 3}, 1.75},
        {{0, 0, -3}, 1.75}}},
      {"plane", "plane: {normal: [0, 2, 0], offset: 1}", {{{5, 3, -2}, 4.0}, {{0, -3, 0}, -2.0}}},
      {"capsule",
       "capsule: {a: [0, 0, 0], b: [0, 2, 0], radius: 0.5}",
       {{{1, 1, 0}, 0.5}, {{0, -1, 0}, 0.5}, {{0, 4, 0}, 1.5}, {{0, 1, 0}, -0.5}}},
      {"cylinder",
       "cylinder: {radius: 1, half_height: 2}",
       {{{3, 0, 0}, 2.0},
        {{0, 5, 0}, 3.0},
        {{0, -5, 0}, 3.0},
        {{2, 3, 0}, kSqrt2},
        {{-2, -3, 0}, kSqrt2},
        {{0, 0, 0}, -1.0}}},
      // Probed on both sides of the axis, and far along it (no caps).
      {"infinite_cylinder",
       "infinite_cylinder: {center: [1, 0, 2], radius: 0.5}",
       {{{1, 7, 2}, -0.5}, {{4, -3, 2}, 2.5}, {{-2, 5, 2}, 2.5}, {{1, 15, 5}, 2.5}, {{1, -15, -1}, 2.5}}},
      // A vertex, a face's inside (its plane), an edge, the centre; both sides of each plane.
      {"octahedron",
       "octahedron: {center: [1, 2, 3], size: 1}",
       {{{3, 2, 3}, 1.0},
        {{-1, 2, 3}, 1.0},
        {{1, 4, 3}, 1.0},
        {{1, 2, 1}, 1.0},
        {{2, 3, 4}, 2.0 / kSqrt3},
        {{0, 1, 2}, 2.0 / kSqrt3},
        {{2, 3, 3}, std::sqrt(0.5)},
        {{0, 1, 3}, std::sqrt(0.5)},
        {{1, 2, 3}, -1.0 / kSqrt3}}},
      // Flat sides face +-z, corners +-x at radius / cos 30; the caps at y = +-half_height.
      {"hex_prism",
       "hex_prism: {center: [0, 1, 0], radius: 1, half_height: 2}",
       {{{0, 1, 3}, 2.0},
        {{0, 1, -3}, 2.0},
        {{3, 1, 0}, 3.0 - 2.0 / kSqrt3},
        {{-3, 1, 0}, 3.0 - 2.0 / kSqrt3},
        {{0, 6, 0}, 3.0},
        {{0, -4, 0}, 3.0},
        {{0, 1, 0}, -1.0},
        {{0, 1, 1.5}, 0.5}}},
      // A cone of apex (0, 1, 0) over the unit disc at y = -1: in the (r, y) half plane the slant
      // is 2 r + y = 1.
      {"capped_cone",
       "capped_cone: {half_height: 1, bottom_radius: 1, top_radius: 0}",
       {{{0, 3, 0}, 2.0},
        {{0, -3, 0}, 2.0},
        {{2, -1, 0}, 1.0},
        {{0, -1, -2}, 1.0},
        {{1, 1, 0}, 2.0 / std::sqrt(5.0)},
        {{-1, 1, 0}, 2.0 / std::sqrt(5.0)},
        {{0, 0, 0}, -1.0 / std::sqrt(5.0)},
        {{0.5, -0.5, 0}, -0.5 / std::sqrt(5.0)}}},
      {"capped_cone_frustum",
       "capped_cone: {center: [0, 2, 0], half_height: 1, bottom_radius: 2, top_radius: 1}",
       {{{0, 5, 0}, 2.0}, {{0, -1, 0}, 2.0}, {{4, 1, 0}, 2.0}, {{0, 2, 0}, -1.0}}},
      // Quilez's bound is exact on the axes outside.
      {"ellipsoid",
       "ellipsoid: {center: [1, 0, 0], radii: [1, 0.5, 0.75]}",
       {{{3, 0, 0}, 1.0},
        {{-1, 0, 0}, 1.0},
        {{1, 1.5, 0}, 1.0},
        {{1, -1.5, 0}, 1.0},
        {{1, 0, 1.75}, 1.0},
        {{1, 0, -1.75}, 1.0}}},
      // Apex (0, 1, 0), base the unit disc at y = 0: in the (r, y) half plane the slant is r + y = 1.
      {"cone",
       "cone: {center: [0, 1, 0], angle: 45, height: 1}",
       {{{0, 3, 0}, 2.0},
        {{0, -2, 0}, 2.0},
        {{2, 0, 0}, 1.0},
        {{-2, 0, 0}, 1.0},
        {{0, 0, 2}, 1.0},
        {{1, 1, 0}, 1.0 / kSqrt2},
        {{0, 1, -1}, 1.0 / kSqrt2},
        {{0, 0.5, 0}, -0.5 / kSqrt2},
        {{0.2, 0.1, 0}, -0.1}}},
      // Outer radius 1 and half height 2; the rim's quarter circle is about (0.5, 1.5) in (r, y).
      {"rounded_cylinder",
       "rounded_cylinder: {radius: 1, half_height: 2, edge_radius: 0.5}",
       {{{3, 0, 0}, 2.0},
        {{-3, 0, 0}, 2.0},
        {{0, 4, 0}, 2.0},
        {{0, -4, 0}, 2.0},
        {{3.5, 5.5, 0}, 4.5},
        {{0, -5.5, -3.5}, 4.5},
        {{0, 0, 0}, -1.0},
        {{0, 1.8, 0}, -0.2}}},
      // Balls of radius 1 at (1, 0, 0) and 0.5 at (1, 2, 0): the tangent's normal in (r, y) is
      // (sqrt 15, 1) / 4, the line n . q = 1 about a.
      {"round_cone",
       "round_cone: {a: [1, 0, 0], b: [1, 2, 0], radius_a: 1, radius_b: 0.5}",
       {{{1, -3, 0}, 2.0},
        {{1, 4, 0}, 1.5},
        {{4, 1, 0}, (3.0 * std::sqrt(15.0) - 3.0) / 4.0},
        {{1, 1, -3}, (3.0 * std::sqrt(15.0) - 3.0) / 4.0},
        {{-2, 1, 0}, (3.0 * std::sqrt(15.0) - 3.0) / 4.0},
        {{1, 0, 0}, -1.0}}},
      // Radius 0.5 about x = 1, z = 0, from y = 0 to 2; then one along (2, 2, 1) / 3 of length 3.
      {"capped_cylinder",
       "capped_cylinder: {a: [1, 0, 0], b: [1, 2, 0], radius: 0.5}",
       {{{1, 3, 0}, 1.0},
        {{1, -2, 0}, 2.0},
        {{3, 1, 0}, 1.5},
        {{1, 1, -2}, 1.5},
        {{-1, 1, 0}, 1.5},
        {{2, 3, 0}, std::sqrt(1.25)},
        {{1, 1, 0}, -0.5},
        {{1, 1.8, 0}, -0.2}}},
      {"capped_cylinder_slanted",
       "capped_cylinder: {a: [0, 0, 0], b: [2, 2, 1], radius: 1}",
       {{{-2.0 / 3, -2.0 / 3, -1.0 / 3}, 1.0}, {{8.0 / 3, 8.0 / 3, 4.0 / 3}, 1.0}, {{1, 1, 0.5}, -1.0}}},
      // Radius 1 at the origin to 0.5 at (0, 2, 0): capped_cone_frustum's shape; its side's outward
      // normal in (r, y) is (2, 0.5) / sqrt(4.25).
      {"frustum",
       "frustum: {a: [0, 0, 0], b: [0, 2, 0], radius_a: 1, radius_b: 0.5}",
       {{{0, -1, 0}, 1.0},
        {{0, 3, 0}, 1.0},
        {{0.25, 3, 0}, 1.0},
        {{3, 0, 0}, 2.0},
        {{0, 0, -3}, 2.0},
        {{0, 1, 0}, -1.5 / std::sqrt(4.25)}}},
      // A cone along z: apex at (1, 1, 3), base of radius 0.5 about (1, 1, 1).
      {"frustum_cone",
       "frustum: {a: [1, 1, 1], b: [1, 1, 3], radius_a: 0.5, radius_b: 0}",
       {{{1, 1, 4}, 1.0}, {{1, 1, 0}, 1.0}, {{1, 1.25, 0.5}, 0.5}}},
      // The half ring z >= 0 of radius 1: its ends at (+-1, 0, 0).
      {"capped_torus",
       "capped_torus: {angle: 90, major_radius: 1, minor_radius: 0.25}",
       {{{0, 0, 1}, -0.25},
        {{0, 0, 3}, 1.75},
        {{0, 0, -1}, kSqrt2 - 0.25},
        {{0, 2, 1}, 1.75},
        {{3, 0, 0}, 1.75},
        {{-3, 0, 0}, 1.75},
        {{2, 0, -2}, std::sqrt(5.0) - 0.25},
        {{-2, 0, -2}, std::sqrt(5.0) - 0.25}}},
      {"capped_torus_full",
       "capped_torus: {center: [0, 1, 0], angle: 180, major_radius: 1, minor_radius: 0.25}",
       {{{0, 1, -1}, -0.25}, {{0, 1, -3}, 1.75}, {{0, 1, 0}, 0.75}, {{-1, 1, 0}, -0.25}}},
      // Bars x = +-1 for |y| <= 1, half circles about (0, +-1, 0) beyond.
      {"link",
       "link: {half_length: 1, major_radius: 1, minor_radius: 0.25}",
       {{{1, 0, 0}, -0.25},
        {{-1, 0.5, 0}, -0.25},
        {{3, 0, 0}, 1.75},
        {{0, 3, 0}, 0.75},
        {{0, -3, 0}, 0.75},
        {{0, 0, 0}, 0.75},
        {{0, 0, 2}, std::sqrt(5.0) - 0.25},
        {{0, 1, 0}, 0.75},
        {{0, -1, 0}, 0.75}}},
      // The cap y >= 0.6 of the unit ball: its rim (0.8, 0.6) in (r, y).
      {"cut_sphere",
       "cut_sphere: {radius: 1, cut_height: 0.6}",
       {{{0, 3, 0}, 2.0},
        {{0, 0, 0}, 0.6},
        {{0, -2, 0}, 2.6},
        {{2, 0.6, 0}, 1.2},
        {{0, 0.6, -2}, 1.2},
        {{0, 0.7, 0}, -0.1},
        {{1.5, 2, 0}, 1.5},
        {{0, 2, -1.5}, 1.5}}},
      {"cut_sphere_below_centre",
       "cut_sphere: {center: [1, 0, 0], radius: 1, cut_height: -0.6}",
       {{{1, -3, 0}, 2.4}, {{1, 0, 0}, -0.6}, {{3.5, 0, 0}, 1.5}, {{1, 0, -2.5}, 1.5}}},
      // Base corners (+-1, 0, +-1), apex (0, 2, 0): the sides' planes 2 |x| + y = 2 and 2 |z| + y = 2.
      {"pyramid",
       "pyramid: {half_width: 1, height: 2}",
       {{{0, -1, 0}, 1.0},
        {{0, 5, 0}, 3.0},
        {{0, 0.5, 0}, -0.5},
        {{2, 1, 0}, 3.0 / std::sqrt(5.0)},
        {{-2, 1, 0}, 3.0 / std::sqrt(5.0)},
        {{0, 1, 2}, 3.0 / std::sqrt(5.0)},
        {{0, 1, -2}, 3.0 / std::sqrt(5.0)},
        {{2, -1, 2}, kSqrt3},
        {{-2, -1, -2}, kSqrt3}}},
      {"triangle",
       "triangle: {a: [0, 0, 0], b: [2, 0, 0], c: [0, 2, 0], thickness: 0.1}",
       {{{0.5, 0.5, 1}, 0.9},
        {{0.5, 0.5, -2}, 1.9},
        {{-1, -1, 0}, kSqrt2 - 0.1},
        {{1, -1, 0}, 0.9},
        {{2, 2, 0}, kSqrt2 - 0.1},
        {{0.5, 0.5, 0}, -0.1},
        {{1, -1, 1}, kSqrt2 - 0.1}}},
      {"quad",
       "quad: {a: [-1, 1, -1], b: [1, 1, -1], c: [1, 1, 1], d: [-1, 1, 1], thickness: 0.1}",
       {{{0, 3, 0}, 1.9},
        {{0.5, -1, 0.5}, 1.9},
        {{3, 1, 0}, 1.9},
        {{2, 1, 2}, kSqrt2 - 0.1},
        {{0, 1, 0}, -0.1},
        {{0, 2, 3}, std::sqrt(5.0) - 0.1},
        {{-3, 1, 0}, 1.9}}},
      // A parallelogram of normal (-1, 0, 2) / sqrt 5 about (1, 1, 0.5).
      {"quad_tilted",
       "quad: {a: [0, 0, 0], b: [2, 0, 1], c: [2, 2, 1], d: [0, 2, 0], thickness: 0.1}",
       {{{1.0 - 1.0 / std::sqrt(5.0), 1, 0.5 + 2.0 / std::sqrt(5.0)}, 0.9}, {{1, 1, 0.5}, -0.1}}},
      // Corners (0, 1), (+-sqrt 3 / 2, -1 / 2) in xy, |z| <= 2. On the faces' normals through their
      // middles the bound is the distance; above the apex it is only half of it.
      {"triangular_prism",
       "triangular_prism: {radius: 1, half_length: 2}",
       {{{0, -1.5, 0}, 1.0},
        {{0, 0, 3}, 1.0},
        {{0, 0, -3}, 1.0},
        {{0, 0, 0}, -0.5},
        {{3.0 * kSqrt3 / 4.0, 0.75, 0}, 1.0},
        {{-3.0 * kSqrt3 / 4.0, 0.75, 0}, 1.0},
        {{0, 3, 0}, 1.0}}},
      // The sector within 60 degrees of +y of the ball of radius 2: its side ends at (sqrt 3, 1) in (r, y).
      {"solid_angle",
       "solid_angle: {angle: 60, radius: 2}",
       {{{0, 3, 0}, 1.0},
        {{0, 1, 0}, -kSqrt3 / 2.0},
        {{0, -1, 0}, 1.0},
        {{2, 0, 0}, 1.0},
        {{-2, 0, 0}, 1.0},
        {{0, 0, 2}, 1.0}}},
      // Wider than a half space: the side ends at (sqrt 3 / 2, -1 / 2).
      {"solid_angle_wide",
       "solid_angle: {center: [0, 1, 0], angle: 120, radius: 1}",
       {{{0, -1, 0}, kSqrt3}, {{0, 3, 0}, 1.0}, {{0, 1.5, 0}, -0.5}}},
      // The unit sphere below y = 0.6, the rim at (0.8, 0.6) in (r, y), 0.1 thick on each side.
      {"cut_hollow_sphere",
       "cut_hollow_sphere: {radius: 1, cut_height: 0.6, thickness: 0.1}",
       {{{0, -3, 0}, 1.9},
        {{0, 0, 0}, 0.9},
        {{0, 3, 0}, std::sqrt(6.4) - 0.1},
        {{2, 0, 0}, 0.9},
        {{0, 0, -2}, 0.9},
        {{0, -1, 0}, -0.1},
        {{1.6, 1.2, 0}, 0.9},
        {{0, 1.2, -1.6}, 0.9}}},
      // Unit balls at 0 and (1, 0, 0): they meet in the circle x = 1/2 of radius sqrt 3 / 2.
      {"death_star",
       "death_star: {radius: 1, carve_radius: 1, carve_distance: 1}",
       {{{-3, 0, 0}, 2.0},
        {{0, 3, 0}, 2.0},
        {{0, 0, -3}, 2.0},
        {{0.5, 0, 0}, 0.5},
        {{-0.5, 0, 0}, -0.5},
        {{2, 0, 0}, kSqrt3}}},
      // Half diagonals 2 (x) and 1 (z), grown by 0.1, |y| <= 0.5: the side x + 2 z = 2 in the quarter.
      {"rhombus",
       "rhombus: {half_width: 2, half_depth: 1, half_height: 0.5, corner_radius: 0.1}",
       {{{0, 2, 0}, 1.5},
        {{0, -2, 0}, 1.5},
        {{4, 0, 0}, 1.9},
        {{-4, 0, 0}, 1.9},
        {{0, 0, 2}, 0.9},
        {{0, 0, -2}, 0.9},
        {{0, 0, 0}, -0.5},
        {{1.0 + 1.0 / std::sqrt(5.0), 0, 0.5 + 2.0 / std::sqrt(5.0)}, 0.9},
        {{-1.0 - 1.0 / std::sqrt(5.0), 0, -0.5 - 2.0 / std::sqrt(5.0)}, 0.9}}},
      // The unit sphere stretched along x into a capsule of half length 1.
      {"elongate",
       "elongate: {h: [1, 0, 0], children: [{sphere: {radius: 1}}]}",
       {{{3, 0, 0}, 1.0}, {{-2.5, 0, 0}, 0.5}, {{0.5, 2, 0}, 1.0}, {{0.5, 0, 0}, -1.0}, {{-0.5, 0, -3}, 2.0}}},
      {"onion",
       "onion: {thickness: 0.1, children: [{sphere: {radius: 1}}]}",
       {{{0, 0, 0}, 0.9}, {{1, 0, 0}, -0.1}, {{0, -2, 0}, 0.9}, {{0, 0, 1.05}, -0.05}}},
      {"round",
       "round: {radius: 0.5, children: [{box: {half_size: [1, 1, 1]}}]}",
       {{{3, 0, 0}, 1.5}, {{0, -3, 0}, 1.5}, {{2, 2, 2}, kSqrt3 - 0.5}, {{0, 0, 0}, -1.5}}},
      {"mirror",
       "mirror: {axes: [x, z], children: [{sphere: {center: [2, 1, 2], radius: 1}}]}",
       {{{2, 1, 2}, -1.0},
        {{-2, 1, 2}, -1.0},
        {{2, 1, -2}, -1.0},
        {{-2, 1, -2}, -1.0},
        {{-2, -1, -2}, 1.0},
        {{0, 1, 2}, 1.0}}},
      // Four copies at 0, 90, 180 and 270 degrees about y.
      {"repeat_polar",
       "repeat_polar: {count: 4, children: [{sphere: {center: [2, 0, 0], radius: 0.5}}]}",
       {{{2, 0, 0}, -0.5},
        {{0, 0, 2}, -0.5},
        {{-2, 0, 0}, -0.5},
        {{0, 0, -2}, -0.5},
        {{3, 0, 0}, 0.5},
        {{0, 1, -2}, 0.5}}},
      // Copies at x = -2, 0, 2 only.
      {"repeat_limited",
       "repeat_limited: {period: [2, 0, 0], min: [-1, 0, 0], max: [1, 0, 0], children: [{sphere: {radius: 0.5}}]}",
       {{{2, 0, 0}, -0.5},
        {{-2, 0, 0}, -0.5},
        {{0, 0, 0}, -0.5},
        {{4, 0, 0}, 1.5},
        {{-6, 0, 0}, 3.5},
        {{0, 3, 0}, 2.5}}},
      // The profiles (2D primitives), alone prisms along z: the distance in the xy plane.
      {"circle", "circle: {center: [1, 2, 0], radius: 0.5}", {{{3, 2, 7}, 1.5}, {{1, 2, -4}, -0.5}}},
      {"rectangle",
       "rectangle: {half_width: 0.5, half_height: 0.25}",
       {{{2, 0, -3}, 1.5}, {{0, 1, 0}, 0.75}, {{1.5, 1.25, 5}, std::sqrt(2.0)}, {{0, 0, 9}, -0.25}}},
      {"rounded_rectangle",
       "rounded_rectangle: {half_width: 0.5, half_height: 0.25, radius: 0.1}",
       {{{0.8, 0.65, 0}, std::sqrt(0.41) - 0.1}, {{2, 0, 0}, 1.5}, {{0, 0, 0}, -0.25}}},
      {"segment", "segment: {a: [-0.5, 0, 0], b: [0.5, 0, 0], radius: 0.05}", {{{0, 1, 9}, 0.95}, {{1.5, 0, 0}, 0.95}}},
      // A hexagon of corner radius 0.5: a corner on +x, a flat side's middle at 30 degrees (apothem
      // 0.5 cos 30).
      {"regular_polygon",
       "regular_polygon: {radius: 0.5, sides: 6}",
       {{{2, 0, 3}, 1.5},
        {{2 * std::cos(M_PI / 6), 2 * std::sin(M_PI / 6), 0}, 2 - 0.5 * std::cos(M_PI / 6)},
        {{0, 0, 0}, -0.5 * std::cos(M_PI / 6)}}},
      // A circle of radius 0.25 at x = 0.5 turned about y 0.5 off the axis: the torus of radii 1 and
      // 0.25.
      {"revolve",
       "revolve: {offset: 0.5, children: [{circle: {center: [0.5, 0, 0], radius: 0.25}}]}",
       {{{0, 0, 2}, 0.75}, {{0, 1, 0}, std::sqrt(2.0) - 0.25}, {{-1, 0, 0}, -0.25}}},
      // A rectangle extruded: the box of half sizes 0.5, 0.25, 1.
      {"extrude",
       "extrude: {half_length: 1, children: [{rectangle: {half_width: 0.5, half_height: 0.25}}]}",
       {{{0, 0, 3}, 2.0}, {{2, 0, 0}, 1.5}, {{1.5, 1.25, 2}, std::sqrt(3.0)}, {{0, 0, 0}, -0.25}}},
      // A unit sphere on the twist's axis: on the axis the factor is (a + sqrt(a^2 + 4)) / 2 with
      // a = rate * 1 (the sphere's reach), and the turned sphere's ball (radius sqrt 2) gives more.
      // At (1.2, 0, 0) the turn is 0: the sphere's distance 0.2 over the factor at a = 1.2 rate.
      {"twist",
       "twist: {rate: 90, children: [{sphere: {radius: 1}}]}",
       {{{0, 3, 0}, 3.0 - std::sqrt(2.0)},
        {{1.2, 0, 0}, 0.2 / (0.5 * (0.6 * M_PI + std::sqrt(0.36 * M_PI * M_PI + 4.0)))}}},
      // Bend's factor is 1 + rate max(r, reach): at (0, 1.2, 0) (x = 0, no turn) 0.2 / (1 + 1.2 rate).
      {"bend",
       "bend: {rate: 30, children: [{sphere: {radius: 1}}]}",
       {{{0, 1.2, 0}, 0.2 / (1.0 + 0.2 * M_PI)}, {{0, 0, 5}, 5.0 - std::sqrt(2.0)}}},
      // A unit sphere stretched twice along x: its distance at p / (2, 1, 1), times 1.
      {"nonuniform_scale",
       "nonuniform_scale: {factors: [2, 1, 1], children: [{sphere: {radius: 1}}]}",
       {{{3, 0, 0}, 0.5}, {{0, 3, 0}, 2.0}, {{0, 0, 0}, -1.0}}},
      // User GLSL: a box turned by p.xz *= rot(a) (vector x matrix, transpose(m)·p), over lipschitz
      // 2. At (0, 0, 2) the turned point is (sin a · 2, 0, cos a · 2) with a = 30°: (1, 0, 1.732),
      // 0.732 beyond the box's face z = 1, halved.
      {"glsl",
       "glsl: {code: 'mat2 rot(float a) { float c = cos(a), s = sin(a); return mat2(c, s, -s, c); } float map(vec3 p) "
       "{ p.xz *= rot(radians(30.0)); vec3 q = abs(p) - vec3(1.0); return length(max(q, 0.0)) + min(max(q.x, "
       "max(q.y, q.z)), 0.0); }', lipschitz: 2}",
       {{{0, 0, 2}, 0.5 * (std::sqrt(3.0) - 1.0)}, {{0, 0, 0}, -0.5}, {{0, 3, 0}, 1.0}}},
      {"union",
       "union: [{sphere: {radius: 1}}, {sphere: {center: [1.5, 0, 0], radius: 1}}]",
       {{{0, 0, 0}, -1.0}, {{3, 0, 0}, 0.5}}},
      {"intersection",
       "intersection: [{sphere: {radius: 1}}, {sphere: {center: [1.5, 0, 0], radius: 1}}]",
       {{{0.75, 0, 0}, -0.25}, {{0, 0, 0}, 0.5}}},
      {"subtraction",
       "subtraction: [{sphere: {radius: 1}}, {sphere: {center: [1.5, 0, 0], radius: 1}}]",
       {{{0, 0, 0}, -0.5}, {{1, 0, 0}, 0.5}}},
      // The polynomial smooth minimum is min(a, b) - k h^2 / 4 with h = max(k - |a - b|, 0) / k: at
      // a == b that is a - k/4; at |a - b| = k/2 (x = 0.875: a = -0.125, b = -0.375) it takes k/16;
      // beyond |a - b| >= k it is the hard min. The smooth maximum adds what the minimum takes.
      {"smooth_union",
       "smooth_union: {k: 0.5, children: [{sphere: {radius: 1}}, {sphere: {center: [1.5, 0, 0], radius: 1}}]}",
       {{{0.75, 0, 0}, -0.375}, {{0.875, 0, 0}, -0.375 - 0.5 / 16}, {{-3, 0, 0}, 2.0}}},
      {"smooth_intersection",
       "smooth_intersection: {k: 0.5, children: [{sphere: {radius: 1}}, {sphere: {center: [1.5, 0, 0], radius: 1}}]}",
       {{{0.75, 0, 0}, -0.125}, {{0.875, 0, 0}, -0.125 + 0.5 / 16}, {{-0.5, 0, 0}, 1.0}}},
      // Subtracting a sphere from itself: at the surface a = -b = 0 and the blend adds k/4. Two
      // spheres, at x = 1.875: a = 0.875, -b = 0.625, |a + b| = k/2.
      {"smooth_subtraction",
       "smooth_subtraction: {k: 0.5, children: [{sphere: {radius: 1}}, {sphere: {radius: 1}}]}",
       {{{1, 0, 0}, 0.125}, {{0, 3, 0}, 2.0}}},
      {"smooth_subtraction_blend",
       "smooth_subtraction: {k: 0.5, children: [{sphere: {radius: 1}}, {sphere: {center: [1.5, 0, 0], radius: 1}}]}",
       {{{1.875, 0, 0}, 0.875 + 0.5 / 16}, {{-0.5, 0, 0}, -0.5}}},
      // The blends on the half spaces a = x (x <= 0) and b = y (y <= 0), or b = -y for the
      // differences, so that a minus b is the same corner: the plane of (a, b) is the xy plane.
      // Chamfer r = 1: the bevel x + y = 1, (a + b - r) / sqrt 2 from it.
      {"union_chamfer",
       "union_chamfer: {radius: 1, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, 0]}}]}",
       {{{0.5, 0.5, 0}, 0.0}, {{1, 1, 3}, 1.0 / kSqrt2}, {{3, 0.2, 0}, 0.2}, {{-1, 2, 0}, -1.0}}},
      {"intersection_chamfer",
       "intersection_chamfer: {radius: 1, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, 0]}}]}",
       {{{-0.5, -0.5, 0}, 0.0}, {{-1, -1, 0}, -1.0 / kSqrt2}, {{2, -3, 0}, 2.0}}},
      {"difference_chamfer",
       "difference_chamfer: {radius: 1, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, -1, 0]}}]}",
       {{{-0.5, -0.5, 0}, 0.0}, {{-1, -1, 0}, -1.0 / kSqrt2}, {{-3, 2, 0}, 2.0}}},
      // Round r = 1: the quarter circle of radius 1 about (1, 1) (union) or (-1, -1).
      {"union_round",
       "union_round: {radius: 1, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, 0]}}]}",
       {{{0.5, 0.5, 0}, 1.0 - 1.0 / kSqrt2},
        {{1 - 1 / kSqrt2, 1 - 1 / kSqrt2, 0}, 0.0},
        {{2, 0.5, 0}, 0.5},
        {{3, 2, 0}, 2.0},
        {{-1, 0.5, 0}, 1.0 - std::hypot(2.0, 0.5)}}},
      {"intersection_round",
       "intersection_round: {radius: 1, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, 0]}}]}",
       {{{-0.5, -0.5, 0}, 1.0 / kSqrt2 - 1.0}, {{1, 0.5, 0}, 1.5}, {{-3, -2, 0}, -2.0}, {{0.5, -2, 0}, 0.5}}},
      {"difference_round",
       "difference_round: {radius: 1, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, -1, 0]}}]}",
       {{{-0.5, -0.5, 0}, 1.0 / kSqrt2 - 1.0}, {{1, 0.5, 0}, 1.5}, {{-3, -2, 0}, -2.0}}},
      // Stairs r = 1, 2 steps: outer corners (0.25, 0.75) and (0.75, 0.25), max(a - corner.a,
      // b - corner.b) from the nearer; 1 step: the corner (0.5, 0.5).
      {"union_stairs",
       "union_stairs: {radius: 1, steps: 2, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, 0]}}]}",
       {{{0.25, 0.75, 0}, 0.0}, {{0.5, 0.5, 0}, 0.25}, {{1, 1, 0}, 0.75}, {{0.1, 0.1, 0}, -0.15}, {{3, 0.1, 0}, 0.1}}},
      {"union_stairs_one_step",
       "union_stairs: {radius: 1, steps: 1, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, 0]}}]}",
       {{{0.5, 0.5, 0}, 0.0}, {{1, 1, 0}, 0.5}, {{0.2, 0.9, 0}, 0.2}}},
      {"intersection_stairs",
       "intersection_stairs: {radius: 1, steps: 2, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, "
       "0]}}]}",
       {{{-0.25, -0.75, 0}, 0.0}, {{-1, -1, 0}, -0.75}, {{2, -3, 0}, 2.0}}},
      {"difference_stairs",
       "difference_stairs: {radius: 1, steps: 2, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, -1, "
       "0]}}]}",
       {{{-0.25, -0.75, 0}, 0.0}, {{-1, -1, 0}, -0.75}, {{-3, 2, 0}, 2.0}}},
      // Columns r = 1: one column of radius c = 1 / (2 + sqrt 2) centred at (c, c), its tip on the
      // bevel's middle (0.5, 0.5); two of radius c = 1 / (2 + 2 sqrt 2) centred at (0.5, c) and
      // (c, 0.5), tips at (0.5, c) + c (1, 1) / sqrt 2. At (1, 1), 1 / sqrt 2 from the one column.
      {"union_columns",
       "union_columns: {radius: 1, steps: 1, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, 0]}}]}",
       {{{0.5, 0.5, 0}, 0.0}, {{1, 1, 0}, 1.0 / kSqrt2}, {{3, 0.2, 0}, 0.2}}},
      {"union_columns_two",
       "union_columns: {radius: 1, steps: 2, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, 0]}}]}",
       {{{0.5 + kColumn2 / kSqrt2, kColumn2 * (1 + 1 / kSqrt2), 0}, 0.0}, {{0.5, 0.5, 0}, 0.5 - 2 * kColumn2}}},
      {"intersection_columns",
       "intersection_columns: {radius: 1, steps: 1, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, "
       "0]}}]}",
       {{{-0.5, -0.5, 0}, 0.0}, {{-1, -1, 0}, -1.0 / kSqrt2}}},
      {"difference_columns",
       "difference_columns: {radius: 1, steps: 1, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, -1, "
       "0]}}]}",
       {{{-0.5, -0.5, 0}, 0.0}, {{-1, -1, 0}, -1.0 / kSqrt2}}},
      // Spheres of radius 1 at 0 and 1.5: inside both at x = 0.75 (a = b = -0.25), one at 0.
      {"xor",
       "xor: [{sphere: {radius: 1}}, {sphere: {center: [1.5, 0, 0], radius: 1}}]",
       {{{0.75, 0, 0}, 0.25}, {{0, 0, 0}, -0.5}, {{3, 0, 0}, 0.5}, {{-2, 0, 0}, 1.0}}},
      // The tube of radius 0.25 about the z axis, where x = y = 0.
      {"pipe",
       "pipe: {radius: 0.25, children: [{plane: {normal: [1, 0, 0]}}, {plane: {normal: [0, 1, 0]}}]}",
       {{{1, 1, 0}, kSqrt2 - 0.25}, {{0, 0, 5}, -0.25}, {{0.3, -0.4, 0}, 0.25}}},
      // Cut into (or raised on) the half space y <= 0 along the plane x = 0.
      {"engrave",
       "engrave: {radius: 0.5, children: [{plane: {normal: [0, 1, 0]}}, {plane: {normal: [1, 0, 0]}}]}",
       {{{0, 0, 0}, 0.5 / kSqrt2}, {{0, -1, 0}, -0.5 / kSqrt2}, {{2, -1, 0}, -1.0}, {{-0.25, -0.25, 0}, 0.0}}},
      {"groove",
       "groove: {ra: 0.5, rb: 0.25, children: [{plane: {normal: [0, 1, 0]}}, {plane: {normal: [1, 0, 0]}}]}",
       {{{0, 0, 0}, 0.25}, {{0, -0.75, 0}, -0.25}, {{1, -0.25, 0}, -0.25}, {{-0.1, -0.5, 0}, 0.0}}},
      {"tongue",
       "tongue: {ra: 0.5, rb: 0.25, children: [{plane: {normal: [0, 1, 0]}}, {plane: {normal: [1, 0, 0]}}]}",
       {{{0, 0.25, 0}, -0.25}, {{0, 1, 0}, 0.5}, {{1, 0.25, 0}, 0.25}, {{-0.25, 0.3, 0}, 0.0}}},
      {"three_way_union",
       "union: [{sphere: {radius: 1}}, {sphere: {center: [4, 0, 0], radius: 1}}, {sphere: {center: [8, 0, 0], radius: "
       "1}}]",
       {{{8, 0, 0}, -1.0}, {{6, 0, 0}, 1.0}}},
      // Box half [1, 2, 3] turned about z by 90 degrees becomes half (2, 1, 3) in the world.
      {"rotate_z", "box: {half_size: [1, 2, 3], rotate: [0, 0, 90]}", {{{3, 0, 0}, 1.0}, {{0, 2, 0}, 1.0}}},
      {"rotate_x", "box: {half_size: [1, 2, 3], rotate: [90, 0, 0]}", {{{0, 4, 0}, 1.0}, {{0, 0, 3}, 1.0}}},
      {"rotate_y", "box: {half_size: [1, 2, 3], rotate: [0, 90, 0]}", {{{4, 0, 0}, 1.0}, {{0, 0, 2}, 1.0}}},
      // Scale 2 about the origin, then the shift: half (4, 2, 6) centred at (0, 0, 10).
      {"scale_translate",
       "box: {half_size: [1, 2, 3], rotate: [0, 0, 90], scale: 2, translate: [0, 0, 10]}",
       {{{5, 0, 10}, 1.0}, {{0, 3, 10}, 1.0}, {{0, 0, 17}, 1.0}}},
      // Period 2 along x and z: (4, 0, 0) is a sphere centre; y is not repeated.
      {"repeat",
       "repeat: {period: [2, 0, 2], children: [{sphere: {radius: 0.5}}]}",
       {{{4, 0, 0}, -0.5}, {{5, 0, 0.5}, std::sqrt(1.25) - 0.5}, {{0, 3, 0}, 2.5}, {{-6, 0, 8}, -0.5}}},
      // (d + 0.1 sin(2x) sin(2y) sin(2z)) / (1 + 0.1 * 2 * sqrt(3)).
      {"displace",
       "displace: {amplitude: 0.1, frequency: 2, children: [{sphere: {radius: 1}}]}",
       {{{0, 2, 0}, 1.0 / (1.0 + 0.2 * kSqrt3)},
        {{0.5, 0.5, 0.5}, (std::sqrt(0.75) - 1.0 + 0.1 * std::pow(std::sin(1.0), 3)) / (1.0 + 0.2 * kSqrt3)}}},
      {"transformed_operator",
       "union: {translate: [0, 5, 0], scale: 3, children: [{sphere: {radius: 1}}]}",
       {{{0, 5, 0}, -3.0}, {{0, 10, 0}, 2.0}}},
      // Far from the set the estimate is the distance to the ball of radius 2^(1/(power-1)) that
      // holds it: |(6, 8, 0)| = 10 from the centre.
      {"mandelbulb",
       "mandelbulb: {center: [1, 2, 3]}",
       {{{1, 2, 13}, 10.0 - std::pow(2.0, 1.0 / 7.0)}, {{7, 10, 3}, 10.0 - std::pow(2.0, 1.0 / 7.0)}}},
      {"mandelbulb_power_2", "mandelbulb: {power: 2}", {{{0, 0, -10}, 8.0}, {{0, 6, 8}, 8.0}}},
      // One level: the cube [-1, 1]^3 with a cross of half width 1/3 cut out. Where one flat wall is
      // nearest the formula is exact; near the edges of the holes it is a bound (at (0.5, 0.5, 0.5),
      // the centre and beyond a tunnel's mouth the true distances are -sqrt(2)/6, sqrt(2)/3 and
      // sqrt(1 + 2/9)).
      {"menger",
       "menger: {iterations: 1}",
       {{{0.9, 0.9, 0.9}, -0.1},
        {{0.5, 0.5, 0.5}, -1.0 / 6.0},
        {{0.5, 0.5, 2}, 1.0},
        {{0.3, 0, 0.5}, 1.0 / 30.0},
        {{0, 0, 0}, 1.0 / 3.0},
        {{2, 0, 0}, 1.0}}},
      {"menger_scaled",
       "menger: {center: [0, 0, 5], half_size: 2, iterations: 3}",
       {{{1, 1, 9}, 2.0}, {{0, -6, 5}, 4.0}}},
      // The tetrahedron's vertices are fixed points of every level: on the set. Far away the
      // estimate is the distance to the ball of radius sqrt(3) size that holds it.
      {"sierpinski",
       "sierpinski: {center: [1, 2, 3]}",
       {{{2, 3, 4}, 0.0}, {{0, 1, 4}, 0.0}, {{11, 2, 3}, 10.0 - std::sqrt(3.0)}, {{1, 2, -7}, 10.0 - std::sqrt(3.0)}}},
      {"sierpinski_sized",
       "sierpinski: {size: 2, iterations: 3, scale: 3}",
       {{{2, -2, -2}, 0.0}, {{0, 0, 12}, 12.0 - 2.0 * std::sqrt(3.0)}}},
      // The Mandelbox's centre is a fixed point of its orbit (the sphere fold scales 0 to 0): |z| = 0.
      // (6, 0, 0) is a cycle of two at scale 2 (6 -> -2 -> 6; dr -> 16 dr + 9 a cycle, 26843545
      // after 12 iterations), (2, 0, 0) and (2, 2, 2) are fixed at scale -1.5 (dr -> 6 dr + 1,
      // (6^13 - 1) / 5 after 12): on the set, |z| / dr. Far away at scale 2 the estimate is the
      // distance to the ball round its cube of half side 6.
      {"mandelbox",
       "mandelbox: {center: [1, 0, 0]}",
       {{{1, 0, 0}, 0.0},
        {{7, 0, 0}, 6.0 / 26843545.0},
        {{41, 0, 0}, 40.0 - 6.0 * std::sqrt(3.0)},
        {{1, 0, -30}, 30.0 - 6.0 * std::sqrt(3.0)}}},
      {"mandelbox_negative",
       "mandelbox: {scale: -1.5, iterations: 12}",
       {{{0, 0, 0}, 0.0},
        {{2, 0, 0}, 2.0 / ((std::pow(6.0, 13) - 1.0) / 5.0)},
        {{2, 2, 2}, 2.0 * std::sqrt(3.0) / ((std::pow(6.0, 13) - 1.0) / 5.0)}}},
      // With c = 0 the Julia set is the unit sphere: outside, the estimate 0.5 r log r stays below
      // the ball's distance r - 1 (or is capped at 1 when it is not); inside, orbits stay (0).
      {"julia_sphere",
       "julia: {center: [0, 1, 0], c: [0, 0, 0, 0]}",
       {{{2, 1, 0}, 1.0}, {{0, 2.5, 0}, 0.5}, {{0, 1, -4}, 3.0}, {{0.6, 1, 0}, 0.0}, {{0, 1, 1}, 0.0}}},
      // Far from the default c's set the distance is that to its ball, R^2 - R = |c|.
      {"julia", "julia: {}", {{{5, 0, 0}, 5.0 - 0.5 * (1.0 + std::sqrt(1.0 + 4.0 * std::sqrt(0.80658025)))}}},
      // Without amplitude the terrain is the flat ground y = height, times the step factor.
      {"terrain",
       "terrain: {height: 0.5, amplitude: 0, step_factor: 0.5}",
       {{{3, 10, -7}, 4.75}, {{100, -2, 50}, -1.25}}},
      {"terrain_derivative", "terrain: {height: -1, amplitude: 0, noise: derivative}", {{{-3, 2, 7}, 3.0}}},
      {"step_factor", "sphere: {radius: 1, scale: 2, step_factor: 0.25}", {{{0, 6, 0}, 1.0}, {{0, 0, 0}, -0.5}}},
      {"step_factor_operator",
       "union: {step_factor: 0.5, children: [{sphere: {radius: 1}}, {box: {center: [3, 0, 0]}}]}",
       {{{0, 3, 0}, 1.0}, {{5, 0, 0}, 0.75}}},
  };
  return cases;
}

Scene scene_for(const SdfCase& c) { return scene_from_yaml("sdf:\n  " + c.sdf_yaml + "\n"); }

std::vector<glm::dvec3> points_of(const SdfCase& c) {
  std::vector<glm::dvec3> points;
  for (const PointCase& p : c.points) points.push_back(p.point);
  return points;
}

void PrintTo(const SdfCase& c, std::ostream* os) { *os << c.name; }

class SdfClosedForm : public ::testing::TestWithParam<SdfCase> {};

TEST_P(SdfClosedForm, ReferenceMatches) {
  const SdfCase& c = GetParam();
  const Scene scene = scene_for(c);
  for (const PointCase& p : c.points) {
    EXPECT_NEAR(reference_distance(scene.sdf, p.point), p.expected, kReferenceTolerance)
        << c.name << " at (" << p.point.x << ", " << p.point.y << ", " << p.point.z << ")";
  }
}

TEST_P(SdfClosedForm, KernelMatchesWithOneAndSixteenLanes) {
  const SdfCase& c = GetParam();
  const Scene scene = scene_for(c);
  for (int lanes : {1, 16}) {
    OpenClOptions options;
    options.lanes = lanes;
    const PointSamples samples = eval_points_opencl(scene, points_of(c), options);
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const PointCase& p = c.points[i];
      EXPECT_NEAR(samples.distance[i], p.expected, kKernelTolerance)
          << c.name << " lanes " << lanes << " at (" << p.point.x << ", " << p.point.y << ", " << p.point.z << ")";
      EXPECT_EQ(samples.distance[i], samples.color_distance[i]) << "map and map_color disagree";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, SdfClosedForm, ::testing::ValuesIn(sdf_cases()),
                         [](const auto& info) { return info.param.name; });

// The catalogue's shapes are written twice, independently: Quilez's closed forms in the kernel, and
// geometric constructions in the reference (the distance to the octahedron's face triangle, to the
// hexagon's and the trapezoid's edges). They must agree everywhere, not only at the probes above.
TEST(SdfClosedForm, CatalogueKernelMatchesTheReferenceEverywhere) {
  const std::set<std::string> catalogue = {
      "octahedron", "hex_prism", "capped_cone", "capped_cone_frustum", "ellipsoid", "elongate", "onion", "round",
      "mirror", "repeat_polar", "repeat_limited",
      // Later catalogue primitives.
      "cone", "rounded_cylinder", "round_cone", "capped_cylinder", "capped_cylinder_slanted", "frustum", "frustum_cone",
      "capped_torus", "capped_torus_full", "link", "cut_sphere", "cut_sphere_below_centre", "pyramid", "triangle",
      "quad", "quad_tilted", "triangular_prism", "solid_angle", "solid_angle_wide", "cut_hollow_sphere", "death_star",
      "rhombus",
      // Profiles and modifiers.
      "circle", "rectangle", "rounded_rectangle", "segment", "regular_polygon", "revolve", "extrude", "twist", "bend",
      "nonuniform_scale"};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-4.0, 4.0);
  std::vector<glm::dvec3> points(400);
  for (glm::dvec3& p : points) p = {coord(rng), coord(rng), coord(rng)};
  std::size_t checked = 0;
  for (const SdfCase& c : sdf_cases()) {
    if (!catalogue.count(c.name)) continue;
    ++checked;
    const Scene scene = scene_for(c);
    const PointSamples samples = eval_points_opencl(scene, points, OpenClOptions{});
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_NEAR(samples.distance[i], reference_distance(scene.sdf, points[i]), kKernelTolerance)
          << c.name << " at (" << points[i].x << ", " << points[i].y << ", " << points[i].z << ")";
    }
  }
  EXPECT_EQ(checked, catalogue.size());
}

TEST(SdfClosedForm, CoversEveryNodeKind) {
  std::set<NodeKind> covered;
  for (const SdfCase& c : sdf_cases()) {
    const Scene scene = scene_for(c);
    covered.insert(scene.sdf.kind);
  }
  for (NodeKind kind : kAllNodeKinds) {
    EXPECT_TRUE(covered.count(kind)) << "no closed-form case for " << node_kind_name(kind);
  }
}

TEST(KernelColor, BlendsLikeTheReference) {
  // Red and blue spheres: the union takes the nearer child's color, the smooth union mixes them
  // with the blend weight (the three.js article's sceneCol): half and half where both are equal.
  const Scene hard = scene_from_yaml(
      "sdf:\n  union: [{sphere: {radius: 1, color: [1, 0, 0]}}, {sphere: {center: [3, 0, 0], radius: 1, color: [0, 0, "
      "1]}}]\n");
  const Scene smooth = scene_from_yaml(
      "sdf:\n  smooth_union: {k: 1, children: [{sphere: {radius: 1, color: [1, 0, 0]}}, "
      "{sphere: {center: [3, 0, 0], radius: 1, color: [0, 0, 1]}}]}\n");
  // Red minus or intersected with blue, nearer: inside the blend band (docs/scene-format.md's color
  // rules), at x = 0.875 the intersection's weight of red is h = 3/4, at x = 1.875 the
  // subtraction's weight of blue is h = 1/4.
  const std::string red_and_blue =
      "{k: 0.5, children: [{sphere: {radius: 1, color: [1, 0, 0]}}, "
      "{sphere: {center: [1.5, 0, 0], radius: 1, color: [0, 0, 1]}}]}";
  const Scene smooth_intersection = scene_from_yaml("sdf:\n  smooth_intersection: " + red_and_blue + "\n");
  const Scene smooth_subtraction = scene_from_yaml("sdf:\n  smooth_subtraction: " + red_and_blue + "\n");
  const std::vector<glm::dvec3> points = {{-1, 0, 0}, {1.5, 0, 0},   {1.4, 0.3, 0},
                                          {4, 0, 0},  {0.875, 0, 0}, {1.875, 0, 0}};
  for (const Scene* scene : {&hard, &smooth, &smooth_intersection, &smooth_subtraction}) {
    for (int lanes : {1, 16}) {
      OpenClOptions options;
      options.lanes = lanes;
      const PointSamples samples = eval_points_opencl(*scene, points, options);
      for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::dvec3 expected = reference_sample(scene->sdf, points[i]).color;
        EXPECT_NEAR(samples.albedo[i].x, expected.x, 1e-5);
        EXPECT_NEAR(samples.albedo[i].y, expected.y, 1e-5);
        EXPECT_NEAR(samples.albedo[i].z, expected.z, 1e-5);
      }
    }
  }
  EXPECT_NEAR(reference_sample(smooth.sdf, {1.5, 0, 0}).color.x, 0.5, 1e-12);
  EXPECT_NEAR(reference_sample(smooth.sdf, {1.5, 0, 0}).color.z, 0.5, 1e-12);
  for (const auto& [scene, point] : {std::pair{&smooth_intersection, glm::dvec3(0.875, 0, 0)},
                                     std::pair{&smooth_subtraction, glm::dvec3(1.875, 0, 0)}}) {
    const glm::dvec3 color = reference_sample(scene->sdf, point).color;
    EXPECT_NEAR(color.x, 0.75, 1e-12);
    EXPECT_NEAR(color.z, 0.25, 1e-12);
  }
}

// The id channel's numbers: primitives in file order through nested operators, the subtracted
// operand where it carves, the heavier operand of a smooth blend, one number for every copy of a
// repeat; from code, from an operand grid of the outer union (numbers from its records) and of a
// nested union (numbers offset by the primitives before it), and in the reference.
TEST(KernelIds, NumberPrimitivesInFileOrder) {
  const std::string yaml =
      "sdf:\n  union:\n"
      "    - sphere: {center: [-3, 0, 0], radius: 0.5}\n"
      "    - smooth_union: {k: 0.2, children: [{sphere: {radius: 0.5}}, {box: {center: [0.8, 0, 0], half_size: [0.3, "
      "0.3, 0.3]}}]}\n"
      "    - subtraction: {children: [{box: {center: [3, 0, 0], half_size: [0.5, 0.5, 0.5]}}, "
      "{sphere: {center: [3, 0.5, 0], radius: 0.3}}]}\n"
      "    - repeat: {period: [0, 0, 2], translate: [0, 3, 0], children: [{sphere: {radius: 0.3}}]}\n"
      "    - union: [{sphere: {center: [0, -3, 0], radius: 0.5}}, {sphere: {center: [0, -3, 2], radius: 0.5}}, "
      "{sphere: {center: [0, -3, 4], radius: 0.5}}]\n";
  // Each point 0.1 outside the surface it is nearest to, or (3, 0.3, 0) inside the box where the
  // sphere carves it.
  const std::vector<std::pair<glm::dvec3, int>> probes = {
      {{-3.6, 0, 0}, 0}, {{-0.6, 0, 0}, 1}, {{1.2, 0, 0}, 2},  {{3.6, 0, 0}, 3},  {{3, 0.3, 0}, 4},
      {{0, 3.4, 0}, 5},  {{0, 3, 2.4}, 5},  {{0, -3.6, 0}, 6}, {{0, -3.6, 2}, 7}, {{0, -3, 4.6}, 8}};
  std::vector<glm::dvec3> points;
  for (const auto& probe : probes) points.push_back(probe.first);
  for (const char* pruning : {"none", "grid"}) {
    for (const std::string& scene_yaml : {yaml, yaml + "render: {subtree_bounds: none}\n"}) {
      Scene scene = scene_from_yaml(scene_yaml);
      scene.render.pruning = std::string(pruning) == "grid" ? Pruning::Grid : Pruning::None;
      for (int lanes : {1, 16}) {
        OpenClOptions options;
        options.lanes = lanes;
        const PointSamples samples = eval_points_opencl(scene, points, options);
        for (std::size_t i = 0; i < probes.size(); ++i) {
          EXPECT_EQ(samples.primitive[i], static_cast<float>(probes[i].second))
              << pruning << " lanes " << lanes << " probe " << i;
          EXPECT_EQ(reference_sample(scene.sdf, points[i]).primitive, probes[i].second) << "probe " << i;
        }
      }
    }
  }
  // With the grid the outer union (5 operands) is evaluated from data; in a scene whose largest
  // union is the nested one (6 operands) its records number from 6.
  Scene nested = scene_from_yaml(yaml);
  nested.sdf.children.pop_back();
  nested.sdf.children.push_back(scene_from_yaml(yaml).sdf.children.back());
  nested.sdf.children.back().children.push_back(
      scene_from_yaml("sdf: {sphere: {center: [0, -3, 6], radius: 0.5}}").sdf);
  nested.sdf.children.back().children.push_back(
      scene_from_yaml("sdf: {sphere: {center: [0, -3, 8], radius: 0.5}}").sdf);
  nested.sdf.children.back().children.push_back(
      scene_from_yaml("sdf: {sphere: {center: [0, -3, 10], radius: 0.5}}").sdf);
  nested.render.pruning = Pruning::Grid;
  ASSERT_EQ(grid_union(nested), &nested.sdf.children.back());
  const PointSamples samples = eval_points_opencl(nested, {{0, -3.6, 0}, {0, -3, 8.6}, {-3.6, 0, 0}}, OpenClOptions{});
  EXPECT_EQ(samples.primitive, (std::vector<float>{6.0f, 10.0f, 0.0f}));
}

}  // namespace
}  // namespace clmarch
