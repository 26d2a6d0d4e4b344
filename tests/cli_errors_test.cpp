// Bad input through the real executable: each case must give one line naming the file, position
// or option, a non-zero exit, no crash and no output file.
#include "common/errors.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

namespace clmarch {
namespace {

using testing::run_clmarch;
using testing::TempDir;

struct BadInputCase {
  std::string name;
  /// Scene file text written to DIR/scene.yaml; empty: no file is written.
  std::string scene;
  /// Arguments; "DIR" is replaced by the temp folder.
  std::vector<std::string> args;
  /// Text the one-line message must contain ("DIR" replaced too).
  std::vector<std::string> message_parts;
  int exit_code = kExitBadInput;
};

const std::string kValidScene = "sdf: {sphere: {radius: 1}}\nrender: {width: 16, height: 8}\n";

std::string expand(std::string s, const std::string& dir) {
  for (std::size_t at; (at = s.find("DIR")) != std::string::npos;) s.replace(at, 3, dir);
  return s;
}

/// An SDF tree of 10^9 spheres in ten lines of YAML aliases ("billion laughs").
std::string billion_alias_bomb() {
  std::string yaml = "sdf:\n  union:\n    - &l0 {sphere: {}}\n";
  for (int level = 1; level <= 9; ++level) {
    yaml += "    - &l" + std::to_string(level) + " {union: [";
    for (int k = 0; k < 10; ++k) yaml += (k ? ", *l" : "*l") + std::to_string(level - 1);
    yaml += "]}\n";
  }
  return yaml;
}

std::string many_lights(int count) {
  std::string yaml = "sdf: {sphere: {}}\nlights: [";
  for (int i = 0; i < count; ++i) yaml += "{directional: {direction: [0, 1, 0]}}, ";
  return yaml + "]\n";
}

const std::vector<BadInputCase>& bad_input_cases() {
  static const std::vector<BadInputCase> cases = {
      {"missing_file", "", {"render", "DIR/none.yaml", "-o", "DIR/out.png"}, {"DIR/none.yaml", "cannot read"}},
      {"malformed_yaml",
       "camera: {position: [1, 2\nsdf: {sphere: {}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:", "malformed YAML"}},
      {"unknown_node_kind",
       "sdf:\n  spher: {radius: 1}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:3:", "unknown node kind 'spher'", "sphere"}},
      {"unknown_key",
       "sdf:\n  sphere: {radius: 1, radus: 2}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:23:", "unknown key 'radus'"}},
      {"negative_radius",
       "sdf:\n  sphere: {radius: -1}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:20:", "sdf.sphere.radius must be > 0 (got -1)"}},
      {"wrong_value_type",
       kValidScene + "camera: {fov: wide}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:15:", "camera.fov must be a number", "'wide'"}},
      {"zero_size_in_file",
       "sdf: {sphere: {radius: 1}}\nrender: {width: 0}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:17:", "render.width must be in [1, 65536] (got 0)"}},
      {"zero_size_option",
       kValidScene,
       {"render", "DIR/scene.yaml", "--size", "0x10", "-o", "DIR/out.png"},
       {"--size 0x10"}},
      {"negative_size_option",
       kValidScene,
       {"render", "DIR/scene.yaml", "--size", "-5x10", "-o", "DIR/out.png"},
       {"--size"}},
      {"missing_output_folder",
       kValidScene,
       {"render", "DIR/scene.yaml", "-o", "DIR/no/such/out.png"},
       {"--output DIR/no/such/out.png", "does not exist"}},
      {"unknown_image_extension",
       kValidScene,
       {"render", "DIR/scene.yaml", "-o", "DIR/out.xyz"},
       {"--output", "'.xyz'"}},
      {"buffers_not_exr",
       kValidScene,
       {"render", "DIR/scene.yaml", "--buffers", "DIR/b.png", "-o", "DIR/out.png"},
       {"--buffers", ".exr"}},
      {"unknown_device",
       kValidScene,
       {"render", "DIR/scene.yaml", "--device", "99", "-o", "DIR/out.png"},
       {"--device 99", "no such device"}},
      {"unknown_option", kValidScene, {"render", "DIR/scene.yaml", "--bogus", "-o", "DIR/out.png"}, {"--bogus"}},
      // Issue 29's papercuts: the nearest valid name, the tab, the color's form, a comma in a flow map.
      {"width_option",
       kValidScene,
       {"render", "DIR/scene.yaml", "--width", "320", "-o", "DIR/out.png"},
       {"--width", "did you mean '--size'?"}},
      {"misspelt_option",
       kValidScene,
       {"render", "DIR/scene.yaml", "--outptu", "DIR/out.png"},
       {"did you mean '--output'?"}},
      {"misspelt_key",
       "sdf:\n  sphere: {radius: 1, colr: [1, 0, 0]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:23:", "unknown key 'colr'", "did you mean 'color'?"}},
      {"misspelt_kind",
       "sdf:\n  sphre: {radius: 1}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"unknown node kind 'sphre'", "did you mean 'sphere'?"}},
      {"misspelt_choice",
       kValidScene + "shading: {model: phnog}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"shading.model must be one of", "did you mean 'phong'?"}},
      {"tab_indent",
       "sdf:\n\tsphere: {radius: 1}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:", "malformed YAML", "line 2 column 1 holds a tab"}},
      {"color_word",
       "sdf:\n  sphere: {radius: 1, color: red}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:30:", "must be a color: [r, g, b]", "'red'"}},
      {"unquoted_comma",
       "sdf:\n  sphere: {radius: max(0.1, t)}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:", "unknown key 't)'", "must be quoted", "\"max(0.1, t)\""}},
      {"unknown_function",
       "sdf:\n  sphere: {radius: \"frac(t) + 1\"}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "frac", "the functions abs,", "fract", "smoothstep", "the variable t"}},
      {"atan_three_arguments",
       "sdf:\n  sphere: {radius: \"atan(1, 2, 3)\"}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "atan takes one argument (y) or two (y, x), not 3"}},
      {"set_empty_value",
       kValidScene,
       {"render", "DIR/scene.yaml", "--set", "render.epsilon=", "-o", "DIR/out.png"},
       {"--set render.epsilon=: the value is empty (null removes the key: --set render.epsilon=null)"}},
      {"set_null_absent_key",
       kValidScene + "shading: {specular: 0.5}\n",
       {"render", "DIR/scene.yaml", "--set", "shading.shadows=null", "-o", "DIR/out.png"},
       {"--set shading.shadows=null", "the scene has no shading.shadows to remove"}},
      // Issue 29's lights.
      {"spot_outer_angle_180",
       kValidScene + "lights: [{spot: {position: [0, 4, 0], direction: [0, -1, 0], outer_angle: 180}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:", "lights[0].spot.outer_angle must be in (0, 180) (got 180)"}},
      {"spot_inner_past_outer",
       kValidScene +
           "lights: [{spot: {position: [0, 4, 0], direction: [0, -1, 0], inner_angle: 40, outer_angle: 30}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:", "lights[0].spot.inner_angle must be in [0, 30] (got 40)"}},
      {"spot_without_direction",
       kValidScene + "lights: [{spot: {position: [0, 4, 0]}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:", "lights[0].spot.direction"}},
      {"spot_zero_direction",
       kValidScene + "lights: [{spot: {position: [0, 4, 0], direction: [0, 0, 0]}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:", "lights[0].spot.direction must not be zero"}},
      {"light_range_zero",
       kValidScene + "lights: [{point: {position: [0, 4, 0], range: 0}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:", "lights[0].point.range must be > 0 (got 0)"}},
      {"unknown_falloff",
       kValidScene + "lights: [{point: {position: [0, 4, 0], falloff: inverse_squared}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:", "lights[0].point.falloff must be one of none, inverse_square",
        "did you mean 'inverse_square'?"}},
      {"falloff_on_directional",
       kValidScene + "lights: [{directional: {direction: [0, 1, 0], falloff: inverse_square}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:", "unknown key 'falloff' in lights[0].directional"}},
      {"light_shadows_not_boolean",
       kValidScene + "lights: [{point: {position: [0, 4, 0], shadows: yes}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:", "lights[0].point.shadows"}},
      // Issue 29's materials per node.
      {"shininess_zero",
       "sdf:\n  sphere: {radius: 1, shininess: 0}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.sphere.shininess must be > 0 (got 0)"}},
      {"specular_negative",
       "sdf:\n  sphere: {radius: 1, specular: -1}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.sphere.specular must be >= 0 (got -1)"}},
      {"emission_word",
       "sdf:\n  sphere: {radius: 1, emission: bright}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.sphere.emission must be a color"}},
      // Issue 29's color patterns.
      {"unknown_pattern",
       "sdf:\n  plane: {color: {checkers: {size: 1}}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "unknown key 'checkers' in sdf.plane.color", "did you mean 'checker'?"}},
      {"checker_size_zero",
       "sdf:\n  plane: {color: {checker: {size: 0}}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.plane.color.checker.size must be > 0 (got 0)"}},
      {"checker_three_colors",
       "sdf:\n  plane: {color: {checker: {colors: [1, 0, 0.5]}}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.plane.color.checker.colors must be a list of 2 colors [a, b] (got 3 items)"}},
      {"grid_line_too_wide",
       "sdf:\n  plane: {color: {grid: {size: 1, line_width: 1}}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.plane.color.grid.line_width must be in (0, 1) (got 1)"}},
      {"grid_axes_empty",
       "sdf:\n  plane: {color: {grid: {axes: []}}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.plane.color.grid.axes must be a list of 1 to 3 axes, e.g. [x, z]"}},
      {"stripes_axis_w",
       "sdf:\n  plane: {color: {stripes: {axis: w}}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.plane.color.stripes.axis must be one of x, y, z (got 'w')"}},
      {"color_expression_unknown_function",
       "sdf:\n  plane: {color: [\"fractal(x)\", 0, 0]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.plane.color[0] must be an expression of the point", "fractal"}},
      {"color_expression_comparison",
       "sdf:\n  plane: {color: [\"x < 1\", 0, 0]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.plane.color[0]", "'<' is not taken here at character 3"}},
      {"pattern_above_grid",
       "render: {pruning: grid}\nsdf:\n  union:\n    color: {checker: {}}\n    rotate: [0, 10, 0]\n    children:\n"
       "      - union: [{sphere: {center: [0, 0, 0]}}, {sphere: {center: [3, 0, 0]}}, {sphere: {center: [6, 0, 0]}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml", "a color pattern set above a union of 3 operands"}},
      // Issue 25's sierpinski: its scale is the IFS's, in (1, 4].
      {"sierpinski_scale_one",
       "sdf:\n  sierpinski: {scale: 1}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.sierpinski.scale must be in (1, 4] (got 1)"}},
      // The later catalogue primitives' checks across parameters.
      {"rounded_cylinder_edge_too_large",
       "sdf:\n  rounded_cylinder: {radius: 0.5, half_height: 0.2, edge_radius: 0.3}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.rounded_cylinder.edge_radius must be in [0, 0.2] (got 0.3)"}},
      {"round_cone_one_ball_inside",
       "sdf:\n  round_cone: {a: [0, 0, 0], b: [0, 0.5, 0], radius_a: 1, radius_b: 0.2}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:",
        "sdf.round_cone.radius_a and sdf.round_cone.radius_b must differ by less than |b - a| = 0.5"}},
      {"round_cone_same_points",
       "sdf:\n  round_cone: {a: [0, 1, 0], b: [0, 1, 0]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.round_cone.a and sdf.round_cone.b must differ"}},
      {"cone_right_angle",
       "sdf:\n  cone: {angle: 90}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.cone.angle must be in (0, 90) (got 90)"}},
      {"cut_sphere_cut_beyond_radius",
       "sdf:\n  cut_sphere: {radius: 1, cut_height: 1}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.cut_sphere.cut_height must be in (-radius, radius) = (-1, 1) (got 1)"}},
      {"triangle_on_a_line",
       "sdf:\n  triangle: {a: [0, 0, 0], b: [1, 1, 1], c: [2, 2, 2]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.triangle.a, sdf.triangle.b and sdf.triangle.c must span a plane"}},
      {"quad_not_flat",
       "sdf:\n  quad: {a: [0, 0, 0], b: [1, 0, 0], c: [1, 1, 0], d: [0, 1, 0.5]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "must lie in one plane (corner"}},
      {"quad_not_convex",
       "sdf:\n  quad: {a: [0, 0, 0], b: [1, 0, 0], c: [0.2, 0.2, 0], d: [0, 1, 0]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "must be the corners of a convex quadrilateral"}},
      {"cut_hollow_sphere_cut_below",
       "sdf:\n  cut_hollow_sphere: {radius: 0.5, cut_height: -0.7}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.cut_hollow_sphere.cut_height must be in (-radius, radius) = (-0.5, 0.5) (got -0.7)"}},
      {"death_star_carve_misses",
       "sdf:\n  death_star: {radius: 1, carve_radius: 0.5, carve_distance: 2}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:",
        "sdf.death_star.carve_distance must be in (|radius - carve_radius|, radius + carve_radius) = (0.5, 1.5)"}},
      {"solid_angle_whole_ball",
       "sdf:\n  solid_angle: {angle: 180}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.solid_angle.angle must be in (0, 180) (got 180)"}},
      // Issue 25's mandelbox and julia.
      {"mandelbox_scale_one",
       "sdf:\n  mandelbox: {scale: 1}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.mandelbox.scale must be in [-4, -1) or (1, 4] (got 1)"}},
      {"mandelbox_scale_large",
       "sdf:\n  mandelbox: {scale: -5}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.mandelbox.scale must be in [-4, 4] (got -5)"}},
      {"mandelbox_radii",
       "sdf:\n  mandelbox: {min_radius: 1.5, fixed_radius: 1}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.mandelbox.min_radius must be at most sdf.mandelbox.fixed_radius (got 1.5 > 1)"}},
      {"mandelbox_iterations_fraction",
       "sdf:\n  mandelbox: {iterations: 2.5}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.mandelbox.iterations"}},
      {"julia_c_three",
       "sdf:\n  julia: {c: [0, 0, 0]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.julia.c must be a list of 4 numbers [x, y, z, w] (got 3 items)"}},
      {"julia_c_range",
       "sdf:\n  julia: {c: [0, 0, 3, 0]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.julia.c[2] must be in [-2, 2] (got 3)"}},
      {"julia_iterations_zero",
       "sdf:\n  julia: {iterations: 0}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.julia.iterations must be in [1, 64] (got 0)"}},
      // Issue 25's profiles and modifiers.
      {"twist_of_plane",
       "sdf:\n  twist:\n    rate: 30\n    children: [{plane: {}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:4:", "sdf.twist needs a bounded child: sdf.twist[0] (plane) has no bounding sphere"}},
      {"bend_rate_missing",
       "sdf:\n  bend: {children: [{sphere: {}}]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.bend.rate"}},
      {"rounded_rectangle_radius",
       "sdf:\n  rounded_rectangle: {half_width: 0.5, half_height: 0.2, radius: 0.3}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.rounded_rectangle.radius must be in [0, 0.2] (got 0.3)"}},
      {"segment_point",
       "sdf:\n  segment: {a: [1, 2, 0], b: [1, 2, 5]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.segment.a and sdf.segment.b must differ in x or y"}},
      {"polygon_two_sides",
       "sdf:\n  regular_polygon: {sides: 2}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.regular_polygon.sides must be in [3, 64] (got 2)"}},
      {"nonuniform_scale_zero",
       "sdf:\n  nonuniform_scale: {factors: [1, 0, 1], children: [{sphere: {}}]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.nonuniform_scale.factors[1] must be in [0.001, 1000] (got 0)"}},
      {"revolve_offset_negative",
       "sdf:\n  revolve: {offset: -1, children: [{circle: {}}]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.revolve.offset must be >= 0 (got -1)"}},
      {"extrude_no_child",
       "sdf:\n  extrude: {half_length: 1, children: []}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:", "sdf.extrude needs at least 1 child node (got 0)"}},
      {"no_image_nothing_else",
       kValidScene,
       {"render", "DIR/scene.yaml", "--no-image"},
       {"--no-image leaves nothing to write"}},
      {"no_image_with_output",
       kValidScene,
       {"render", "DIR/scene.yaml", "--no-image", "--stats", "-o", "DIR/out.png"},
       {"--no-image and --output"}},
      {"bad_set_path",
       kValidScene,
       {"render", "DIR/scene.yaml", "--set", "render.epsilonn=1", "-o", "DIR/out.png"},
       {"unknown key 'epsilonn'"}},
      {"bad_set_value",
       kValidScene,
       {"render", "DIR/scene.yaml", "--set", "render.epsilon=-1", "-o", "DIR/out.png"},
       {"(--set)", "render.epsilon must be > 0 (got -1)"}},
      {"set_without_equals",
       kValidScene,
       {"render", "DIR/scene.yaml", "--set", "render.epsilon", "-o", "DIR/out.png"},
       {"--set render.epsilon", "key.path=value"}},
      {"duplicate_key",
       "sdf: {sphere: {radius: 1, radius: 2}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"duplicate key 'radius'"}},
      {"nan_value",
       "sdf: {sphere: {radius: .nan}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"must be finite"}},
      {"missing_sdf", "camera: {fov: 45}\n", {"render", "DIR/scene.yaml", "-o", "DIR/out.png"}, {"sdf", "required"}},
      {"empty_union", "sdf: {union: []}\n", {"render", "DIR/scene.yaml", "-o", "DIR/out.png"}, {"at least 1 child"}},
      {"smooth_without_k",
       "sdf: {smooth_union: [{sphere: {}}, {box: {}}]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"blend radius"}},
      // The blends' parameters: required, ranged, integers; and their least number of children.
      {"chamfer_without_radius",
       "sdf: {union_chamfer: [{sphere: {}}, {box: {}}]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:22:", "sdf.union_chamfer needs radius: write {radius: ..., children: [...]}"}},
      {"round_without_radius",
       "sdf: {union_round: {children: [{sphere: {}}, {box: {}}]}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:20:", "sdf.union_round.radius"}},
      {"stairs_zero_steps",
       "sdf: {union_stairs: {radius: 1, steps: 0, children: [{sphere: {}}, {box: {}}]}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:40:", "sdf.union_stairs.steps must be in [1, 64] (got 0)"}},
      {"columns_fractional_steps",
       "sdf: {union_columns: {radius: 1, steps: 1.5, children: [{sphere: {}}, {box: {}}]}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:41:", "sdf.union_columns.steps must be an integer in decimal digits (got '1.5')"}},
      {"pipe_one_child",
       "sdf: {pipe: {radius: 1, children: [{sphere: {}}]}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:35:", "sdf.pipe needs at least 2 child nodes (got 1)"}},
      {"xor_one_child",
       "sdf: {xor: [{sphere: {}}]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:12:", "sdf.xor needs at least 2 child nodes (got 1)"}},
      {"difference_one_child",
       "sdf: {difference_round: {radius: 1, children: [{sphere: {}}]}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:47:", "sdf.difference_round needs at least 2 child nodes (got 1)"}},
      {"groove_without_rb",
       "sdf: {groove: {ra: 0.1, children: [{sphere: {}}, {box: {}}]}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:15:", "sdf.groove.rb"}},
      {"reference_with_lanes",
       kValidScene,
       {"render", "DIR/scene.yaml", "--backend", "reference", "--lanes", "16", "-o", "DIR/out.png"},
       {"--lanes", "--backend reference"}},
      {"unknown_backend",
       kValidScene,
       {"render", "DIR/scene.yaml", "--backend", "vulkan", "-o", "DIR/out.png"},
       {"--backend"}},
      {"empty_scene_file",
       "# nothing\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml", "empty"}},
      {"alias_bomb",
       billion_alias_bomb(),
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:", "the tree has too many nodes", "expected at most 10000"}},
      {"alias_cycle",
       "sdf: &a {union: [*a]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:6:", "deeper than 64 levels"}},
      {"too_many_lights",
       many_lights(1025),
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:2:9:", "lights has too many entries (got 1025, expected at most 1024)"}},
      {"second_yaml_document",
       kValidScene + "---\nsdf: {box: {}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:1:", "one YAML document"}},
      {"scene_is_a_folder", "", {"render", "DIR", "-o", "DIR/out.png"}, {"DIR: is a folder"}},
      {"infinite_value",
       "sdf: {sphere: {radius: .inf}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:24:", "must be finite (got .inf)"}},
      {"number_beyond_double",
       "sdf: {sphere: {radius: 1e400}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:24:", "the float range (got 1e400)"}},
      {"fraction_for_integer",
       kValidScene + "shading: {reflections: 1.5}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:24:", "shading.reflections must be an integer in decimal digits (got '1.5')"}},
      {"unknown_top_level_key",
       kValidScene + "rendr: {}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:1:", "unknown key 'rendr' in the scene"}},
      {"missing_required_key",
       kValidScene + "lights: [{point: {intensity: 2}}]\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:18:", "lights[0].point.position is required"}},
      {"list_expected",
       kValidScene + "lights: {point: {position: [0, 1, 0]}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:9:", "lights must be a list (got a map)"}},
      {"empty_tree",
       "sdf: {}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:6:", "(got 0 keys)"}},
      {"multi_line_value",
       kValidScene + "camera: {fov: \"wide\\nangle\"}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:3:15:", "'wide\\nangle'"}},
      {"set_value_not_yaml",
       kValidScene,
       {"render", "DIR/scene.yaml", "--set", "render.width=[1", "-o", "DIR/out.png"},
       {"--set render.width=[1: the value is not valid YAML"}},
      {"set_index_past_end",
       "sdf: {union: [{sphere: {}}]}\n",
       {"render", "DIR/scene.yaml", "--set", "sdf.union.3.sphere.radius=2", "-o", "DIR/out.png"},
       {"--set sdf.union.3.sphere.radius=2", "index 3 is past the end of a list of 1"}},
      {"set_alias_cycle",
       kValidScene,
       {"render", "DIR/scene.yaml", "--set", "sdf=&a {union: [*a]}", "-o", "DIR/out.png"},
       {"--set sdf=&a {union: [*a]}: the value nests too deep"}},
      {"size_not_wxh",
       kValidScene,
       {"render", "DIR/scene.yaml", "--size", "big", "-o", "DIR/out.png"},
       {"--size big: expected WIDTHxHEIGHT"}},
      {"size_too_many_pixels",
       kValidScene,
       {"render", "DIR/scene.yaml", "--size", "65536x65536", "-o", "DIR/out.png"},
       {"--size 65536x65536: too many pixels (got 4294967296, expected at most 2147483647)"}},
      {"time_not_finite",
       kValidScene,
       {"render", "DIR/scene.yaml", "--time", "nan", "-o", "DIR/out.png"},
       {"--time: must be a finite number of seconds (got 'nan')"}},
      {"time_past_double",
       kValidScene,
       {"render", "DIR/scene.yaml", "--time", "1e400", "-o", "DIR/out.png"},
       {"--time: must be a finite number of seconds (got '1e400')"}},
      {"time_not_a_number",
       kValidScene,
       {"render", "DIR/scene.yaml", "--time", "0x10", "-o", "DIR/out.png"},
       {"--time: must be a finite number of seconds (got '0x10')"}},
      {"fps_past_double",
       kValidScene,
       {"render", "DIR/scene.yaml", "--frames", "0:1", "--fps", "1e400", "-o", "DIR/out.png"},
       {"--fps: must be frames per second in (0, 1000] (got '1e400')"}},
      {"fps_over_limit",
       kValidScene,
       {"render", "DIR/scene.yaml", "--frames", "0:1", "--fps", "1001", "-o", "DIR/out.png"},
       {"--fps: must be frames per second in (0, 1000] (got '1001')"}},
      {"output_is_a_folder", kValidScene, {"render", "DIR/scene.yaml", "-o", "DIR"}, {"--output DIR: is a folder"}},
      {"output_without_extension",
       kValidScene,
       {"render", "DIR/scene.yaml", "-o", "DIR/out"},
       {"--output DIR/out", "extension"}},
      {"buffers_folder_missing",
       kValidScene,
       {"render", "DIR/scene.yaml", "--buffers", "DIR/no/b.exr", "-o", "DIR/out.png"},
       {"--buffers DIR/no/b.exr", "does not exist"}},
      {"check_out_dir_missing",
       kValidScene,
       {"check", "DIR/scene.yaml", "--out-dir", "DIR/none"},
       {"--out-dir DIR/none: no such folder"}},
      // Messages stay one line whatever they quote: a NUL in the file (yaml-cpp called it an escape,
      // a line later), a newline in a file name or option value.
      {"nul_byte_in_file",
       std::string("sdf: {sphere: {}}\0\nfoo: 1\n", 26),
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:18: the file holds a NUL byte"}},
      {"newline_in_file_name",
       "",
       {"render", "DIR/no\nne.yaml", "-o", "DIR/out.png"},
       {"DIR/no\\nne.yaml: cannot read"}},
      {"newline_in_size",
       kValidScene,
       {"render", "DIR/scene.yaml", "--size", "64\nx36", "-o", "DIR/out.png"},
       {"--size 64\\nx36: expected WIDTHxHEIGHT"}},
      {"set_two_documents",
       kValidScene,
       {"render", "DIR/scene.yaml", "--set", "render=--- {width: 3}\n--- {x: 1}", "-o", "DIR/out.png"},
       {"the value holds 2 YAML documents, expected one"}},
      {"size_side_past_six_digits",
       kValidScene,
       {"render", "DIR/scene.yaml", "--size", "4294967360x36", "-o", "DIR/out.png"},
       {"--size 4294967360x36: width and height must be in [1, 65536]"}},
      {"unknown_command",
       "",
       {"rendr", "DIR/scene.yaml"},
       {"clmarch: unknown command 'rendr' (expected render, check"}},
      {"description_not_text",
       "description: [a, b]\nsdf: {sphere: {}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:14: description must be text (got a list)"}},
      // A 100 KB expression is not echoed whole: its start and the parser's reason stay.
      {"huge_expression",
       "sdf: {sphere: {radius: \"" + std::string(100000, '(') + "\"}}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"DIR/scene.yaml:1:24: sdf.sphere.radius must be a number or an expression of the time t (got '(((",
        "characters ...]", "Expression too long."}},
      // An empty value is a mistake, not the option left out (it rendered with the defaults).
      {"empty_size",
       kValidScene,
       {"render", "DIR/scene.yaml", "--size", "", "-o", "DIR/out.png"},
       {"--size: the value is empty"}},
      {"empty_output", kValidScene, {"render", "DIR/scene.yaml", "-o", ""}, {"--output: the value is empty"}},
      {"empty_device", kValidScene, {"check", "DIR/scene.yaml", "--device", ""}, {"--device: the value is empty"}},
      {"lanes_not_a_width",
       kValidScene,
       {"render", "DIR/scene.yaml", "--lanes", "abc", "-o", "DIR/out.png"},
       {"--lanes: must be 1, 4, 8 or 16 (got 'abc')"}},
      {"repeat_not_an_integer",
       kValidScene,
       {"bench", "DIR/scene.yaml", "--repeat", "abc"},
       {"--repeat: must be an integer from 1 to 1000 (got 'abc')"}},
      {"check_out_dir_is_a_file",
       kValidScene,
       {"check", "DIR/scene.yaml", "--out-dir", "DIR/scene.yaml"},
       {"--out-dir DIR/scene.yaml: is a file, expected a folder"}},
      {"check_out_dir_takes_no_files",
       kValidScene,
       {"check", "DIR/scene.yaml", "--out-dir", "/proc"},
       {"--out-dir /proc/difference.exr: cannot create files in folder /proc"}},
      {"image_and_buffers_same_file",
       kValidScene,
       {"render", "DIR/scene.yaml", "-o", "DIR/out.exr", "--buffers", "DIR/./out.exr"},
       {"--output and --buffers are the same file DIR/./out.exr: one would overwrite the other"}},
      {"image_and_kernel_same_file",
       kValidScene,
       {"render", "DIR/scene.yaml", "-o", "DIR/k.png", "--dump-kernel", "DIR/k.png"},
       {"--output and --dump-kernel are the same file"}},
      {"file_name_too_long",
       kValidScene,
       {"render", "DIR/scene.yaml", "-o", "DIR/" + std::string(252, 'n') + ".png"},
       {"the file name has 256 characters, more than the 255 a folder takes"}},
      {"check_bad_size", kValidScene, {"check", "DIR/scene.yaml", "--size", "0x0"}, {"--size 0x0", "(got 0 x 0)"}},
      {"bench_bad_set_path",
       kValidScene,
       {"bench", "DIR/scene.yaml", "--set", "render.x=1"},
       {"(--set)", "unknown key 'x'"}},
      {"camera_up_parallel",
       "sdf: {sphere: {}}\ncamera: {position: [0, 5, 0], look_at: [0, 0, 0], up: [0, 1, 0]}\n",
       {"render", "DIR/scene.yaml", "-o", "DIR/out.png"},
       {"camera.up"}},
  };
  return cases;
}

void PrintTo(const BadInputCase& c, std::ostream* os) { *os << c.name; }

class BadInput : public ::testing::TestWithParam<BadInputCase> {};

TEST_P(BadInput, OneLineErrorNoOutput) {
  const BadInputCase& c = GetParam();
  TempDir dir;
  if (!c.scene.empty()) std::ofstream(dir / "scene.yaml") << c.scene;
  const std::vector<std::string> before = dir.files();
  std::vector<std::string> args;
  for (const std::string& a : c.args) args.push_back(expand(a, dir.path().string()));
  const testing::CommandResult result = run_clmarch(args);
  EXPECT_EQ(result.exit_code, c.exit_code) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << "expected one line, got:\n" << result.err;
  for (const std::string& part : c.message_parts) {
    EXPECT_NE(result.err.find(expand(part, dir.path().string())), std::string::npos)
        << "message lacks '" << part << "':\n"
        << result.err;
  }
  EXPECT_EQ(dir.files(), before) << "a failed run must leave no file behind";
}

INSTANTIATE_TEST_SUITE_P(Cli, BadInput, ::testing::ValuesIn(bad_input_cases()),
                         [](const auto& info) { return info.param.name; });

TEST(Cli, RenderWritesImageBuffersAndStats) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kValidScene;
  const auto result =
      run_clmarch({"render", (dir / "scene.yaml").string(), "-o", (dir / "out.png").string(), "--buffers",
                   (dir / "b.exr").string(), "--dump-kernel", (dir / "k.cl").string(), "--stats"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"b.exr", "k.cl", "out.png", "scene.yaml"}));
  for (const char* key : {"\"device\"", "\"build_ms\"", "\"kernel_ms\"", "\"steps\"", "\"rays_per_s\""}) {
    EXPECT_NE(result.out.find(key), std::string::npos) << key << " missing from --stats: " << result.out;
  }
}

TEST(Cli, TimeTakesASignedDecimalNumber) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << "sdf: {sphere: {radius: \"1 + 0.1 * t\"}}\nrender: {width: 16, height: 8}\n";
  for (const char* time : {"+1.5", "-1.5", "2e-1", "3"}) {
    const auto result =
        run_clmarch({"render", (dir / "scene.yaml").string(), "--time", time, "-o", (dir / "out.png").string()});
    EXPECT_EQ(result.exit_code, 0) << time << ": " << result.err;
  }
}

TEST(Cli, DefaultOutputIsSceneNamePng) {
  TempDir dir;
  std::ofstream(dir / "ball.yaml") << kValidScene;
  const std::string command =
      "cd '" + dir.path().string() + "' && '" + CLMARCH_BINARY + "' render ball.yaml 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"ball.png", "ball.yaml"}));
}

TEST(Cli, DefaultOutputSaysWhereItWrote) {
  TempDir dir;
  std::ofstream(dir / "ball.yaml") << kValidScene;
  const std::string command = "cd '" + dir.path().string() + "' && '" + CLMARCH_BINARY + "' render ball.yaml 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string err;
  for (char buffer[256]; std::fgets(buffer, sizeof buffer, pipe);) err += buffer;
  ASSERT_EQ(pclose(pipe), 0) << err;
  EXPECT_EQ(err, "clmarch: wrote ball.png\n");
}

TEST(Cli, DevicesListsPocl) {
  const auto result = run_clmarch({"devices"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("0: "), std::string::npos);
  EXPECT_NE(result.out.find("(default)"), std::string::npos);
}

}  // namespace
}  // namespace clmarch
