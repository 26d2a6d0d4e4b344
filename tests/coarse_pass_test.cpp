// The coarse cone pass (render.coarse_pass: cone, issue 6): every block's cone stops before any of
// its rays could hit, in the kernel and in the reference; renders keep their image with fewer
// steps; kernel and reference agree; bad values are one-line errors.
#include "analytic_intersections.hpp"
#include "check/cross_check.hpp"
#include "common/errors.hpp"
#include "device_types.h"
#include "reference/reference_cones.hpp"
#include "reference/reference_renderer.hpp"
#include "render/cone_pass.hpp"
#include "render/device_inputs.hpp"
#include "render/dispatch_plan.hpp"
#include "render/opencl_renderer.hpp"
#include "render/prepared_program.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"
#include "support/tolerances.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>

namespace clmarch {
namespace {

using testing::kFloatRelative;
using testing::scene_from_yaml;
using testing::total_steps;

/// A shipped scene without the pass (the default, auto, runs it for the terrain).
Scene load_scene_without_cones(const std::string& name, int width, int height) {
  Scene scene = load_scene_file(testing::source_path("scenes/" + name).string());
  scene.render.width = width;
  scene.render.height = height;
  scene.render.coarse_pass = CoarsePass::None;
  return scene;
}

Scene with_cones(Scene scene) {
  scene.render.coarse_pass = CoarsePass::Cone;
  return scene;
}

// The starts the kernel's cone pass writes, one per block, row-major.
std::vector<float> kernel_cone_starts(const Scene& scene) {
  OpenClOptions options;
  PreparedProgram program = prepare_program(scene, options, KernelPurpose::DepthSteps);
  std::optional<ConePass> cones = make_cone_pass(program, scene, std::nullopt);
  EXPECT_TRUE(cones.has_value());
  if (!cones) return {};
  const Dispatch dispatch =
      plan_tile_dispatch(program, scene.render.width, scene.render.height, chunk_pixels_for(program.program.device));
  enqueue_cone_pass(program.program.queue, *cones, march_params(scene, dispatch));
  return read_cone_plane(program.program.queue, *cones, cones->starts);
}

FrameBuffers render_normals(const Scene& scene, int lanes = 16) {
  OpenClOptions options;
  options.lanes = lanes;
  options.purpose = KernelPurpose::Normals;
  return render_opencl(scene, options).buffers;
}

// On the torus every ray's first surface is known in closed form. Both passes must start each
// block's rays at least epsilon before it (the field there is >= epsilon: no sample before the
// start could have hit), from a far camera, the scene's and one inside the bounding sphere; and
// the cones must have moved, or the test would hold trivially.
TEST(ConePass, StartsStayBeforeEveryRaysFirstSurface) {
  const std::vector<std::pair<std::string, std::string>> cameras = {
      {"[-2, 4, 4]", "50"}, {"[0.2, 0.9, 2.4]", "70"}, {"[12, 3, -30]", "6"}};
  for (const auto& [position, fov] : cameras) {
    const Scene scene =
        with_cones(scene_from_yaml("camera: {position: " + position + ", look_at: [0.3, 0, 0.1], fov: " + fov +
                                   "}\n"
                                   "render: {width: 83, height: 47, epsilon: 1e-3}\nsdf: {torus: {}}\n"));
    const Torus& torus = std::get<Torus>(scene.sdf.params);
    const CameraBasis basis = camera_basis(scene.camera, scene.render.width, scene.render.height);
    const ConeStarts reference = reference_cone_starts(scene);
    const std::vector<float> kernel = kernel_cone_starts(scene);
    ASSERT_EQ(kernel.size(), reference.start.size());
    const std::optional<BoundingSphere> bounds = camera_ray_bounds(scene);
    ASSERT_TRUE(bounds);
    const double t_first = std::max(glm::length(scene.camera.position - bounds->center) - bounds->radius, 0.0);
    int hits = 0;
    for (int j = 0; j < scene.render.height; ++j) {
      for (int i = 0; i < scene.render.width; ++i) {
        const std::optional<double> exact = intersect_torus(basis.origin, pixel_ray_direction(basis, i, j), torus);
        if (!exact) continue;
        ++hits;
        const std::size_t block =
            static_cast<std::size_t>(j / CLMARCH_COARSE_BLOCK) * reference.blocks_x + i / CLMARCH_COARSE_BLOCK;
        EXPECT_LE(reference.at_pixel(i, j), *exact - scene.render.epsilon) << position << " pixel " << i << "," << j;
        EXPECT_LE(kernel[block], *exact - scene.render.epsilon + kFloatRelative * (1.0 + *exact))
            << position << " pixel " << i << "," << j;
      }
    }
    EXPECT_GT(hits, 150) << position;
    const auto moved =
        std::count_if(reference.start.begin(), reference.start.end(), [&](double t) { return t > t_first + 1e-3; });
    EXPECT_GT(moved, static_cast<long>(reference.start.size() / 4)) << position;
  }
}

// The kernel's float cones follow the reference's double ones: the same starts up to rounding,
// and the same steps but where a stop decision falls within rounding of its bound. Also with
// Crum's glow (the cone's margin, COARSE_MARGIN = its radius) and the pixel-cone hit threshold
// (its slope > 0), which both move the starts by far more than the comparison's tolerance.
TEST(ConePass, KernelStartsMatchTheReference) {
  Scene glowing_cone = load_scene_without_cones("torus.yaml", 160, 90);
  glowing_cone.shading.glow = Glow{glm::dvec3(1.0), 0.2};
  glowing_cone.render.hit_threshold = HitThreshold::PixelCone;
  glowing_cone.render.cone_factor = 2.0;
  glowing_cone.source_name += " with glow and pixel cone";
  for (Scene scene : {load_scene_without_cones("torus.yaml", 160, 90),
                      load_scene_without_cones("terrain_fbm.yaml", 160, 90), glowing_cone}) {
    scene = with_cones(scene);
    const ConeStarts reference = reference_cone_starts(scene);
    const std::vector<float> kernel = kernel_cone_starts(scene);
    ASSERT_EQ(kernel.size(), reference.start.size());
    std::size_t close = 0;
    for (std::size_t b = 0; b < kernel.size(); ++b) {
      if (std::abs(kernel[b] - reference.start[b]) <= 1e-3 * (1.0 + reference.start[b])) ++close;
    }
    EXPECT_GE(close, kernel.size() * 99 / 100) << scene.source_name << ": " << close << " of " << kernel.size();
  }
}

// The image keeps its hits and depths while the camera rays take fewer steps: on exact fields (the
// torus, boxes under the mod tiling) every depth stays within the check's per-pixel tolerance
// (both marches stop within epsilon / cos before the same surface); on a bound (the terrain,
// unbounded, the most to gain) the stop band is wider than that, and only the hits are compared.
TEST(ConePass, SameImageFewerSteps) {
  Scene tiled = load_scene_without_cones("tiled_boxes.yaml", 160, 90);
  tiled.tiling->method = TilingMethod::Mod;
  struct Case {
    Scene scene;
    double most_steps;  // of the plain march's
    bool exact_field;
  };
  const std::vector<Case> cases = {{load_scene_without_cones("torus.yaml", 160, 90), 0.95, true},
                                   {tiled, 0.98, true},
                                   {load_scene_without_cones("terrain_fbm.yaml", 160, 90), 0.7, false}};
  for (const Case& c : cases) {
    const FrameBuffers a = render_normals(c.scene);
    const FrameBuffers b = render_normals(with_cones(c.scene));
    const std::string name = c.scene.source_name;
    EXPECT_LT(total_steps(b), c.most_steps * total_steps(a))
        << name << ": " << total_steps(a) << " -> " << total_steps(b);
    const CheckReport report = cross_check(c.scene, b, a);
    EXPECT_EQ(report.mask_mismatch_interior, 0) << name;
    EXPECT_LE(report.mask_mismatch_silhouette, report.tolerances.mask_mismatch_silhouette) << name;
    if (c.exact_field) {
      EXPECT_LE(report.depth_in_tolerances.max, 1.0) << name;
    }
    EXPECT_GT(report.both_hit, 1000) << name;
  }
}

// `clmarch check` with the cone pass: the reference runs the same pass in double.
TEST(ConePass, KernelAndReferenceAgree) {
  Scene tiled = load_scene_without_cones("tiled_boxes.yaml", 80, 45);
  tiled.tiling->method = TilingMethod::Mod;
  for (const Scene& plain :
       {load_scene_without_cones("torus.yaml", 80, 45), load_scene_without_cones("terrain_fbm.yaml", 80, 45),
        load_scene_without_cones("mandelbulb.yaml", 80, 45), tiled}) {
    const Scene scene = with_cones(plain);
    OpenClOptions options;
    options.purpose = KernelPurpose::Shaded;
    const FrameBuffers opencl = render_opencl(scene, options).buffers;
    const CheckReport report = cross_check(scene, opencl, render_reference(scene), reshade_hits(scene, opencl));
    EXPECT_TRUE(report.passed()) << scene.source_name << ":\n" << report.to_text();
  }
}

// One pixel per work-item (the GPU shape) and 16-lane packets read the same starts.
TEST(ConePass, EveryLaneWidthTakesTheSameSteps) {
  const Scene scene = with_cones(load_scene_without_cones("terrain_fbm.yaml", 67, 41));
  const FrameBuffers one = render_normals(scene, 1);
  const FrameBuffers sixteen = render_normals(scene, 16);
  EXPECT_EQ(one.plane(Channel::Steps), sixteen.plane(Channel::Steps));
  EXPECT_EQ(one.plane(Channel::Depth), sixteen.plane(Channel::Depth));
}

// The cones' own evaluations are counted apart from the pixels' steps, by both renderers.
TEST(ConePass, StatsCountTheConesSteps) {
  const Scene plain = load_scene_without_cones("terrain_fbm.yaml", 96, 54);
  OpenClOptions options;
  options.purpose = KernelPurpose::DepthSteps;
  EXPECT_EQ(render_opencl(plain, options).stats.coarse_steps, 0u);
  const Scene scene = with_cones(plain);
  const RenderStats stats = render_opencl(scene, options).stats;
  const std::vector<int>& steps = reference_cone_starts(scene).steps;
  const double reference_steps = std::accumulate(steps.begin(), steps.end(), 0.0);
  EXPECT_GT(reference_steps, static_cast<double>(steps.size()));
  EXPECT_NEAR(static_cast<double>(stats.coarse_steps), reference_steps, 0.02 * reference_steps);
}

// auto, the default: the pass for a scene whose rays no bounding sphere starts near the surface,
// unless its shading reads the step counts the pass shortens; never under the cells tiling; and
// what a scene sets is kept.
TEST(ConePass, AutoRunsItWhereNoBoundingSphereStartsTheRays) {
  const auto uses = [](const std::string& yaml) { return uses_cone_pass(scene_from_yaml(yaml)); };
  EXPECT_EQ(scene_from_yaml("sdf: {sphere: {}}\n").render.coarse_pass, CoarsePass::Auto);
  EXPECT_TRUE(uses("sdf: {union: [{sphere: {}}, {plane: {}}]}\n")) << "unbounded";
  EXPECT_FALSE(uses("sdf: {sphere: {}}\n")) << "inside its bounding sphere";
  EXPECT_TRUE(uses("sdf: {sphere: {}}\nrender: {bounds: none}\n")) << "bounded, but no sphere clips the rays";
  EXPECT_FALSE(uses("sdf: {union: [{sphere: {}}, {plane: {}}]}\nshading: {step_ao: 3000}\n")) << "step-count occlusion";
  EXPECT_TRUE(uses("tiling: {method: mod}\nsdf: {sphere: {center: [0.5, 0.5, 0.5], radius: 0.3}}\n")) << "mod tiling";
  EXPECT_FALSE(uses("tiling: {method: cells}\nsdf: {sphere: {center: [0.5, 0.5, 0.5], radius: 0.3}}\n"))
      << "cells tiling";
  EXPECT_FALSE(uses("sdf: {union: [{sphere: {}}, {plane: {}}]}\nrender: {coarse_pass: none}\n"));
  EXPECT_TRUE(uses("sdf: {sphere: {}}\nrender: {coarse_pass: cone}\n"));
  // The terrain renders with the pass by default, and with its steps.
  Scene terrain = load_scene_without_cones("terrain_fbm.yaml", 96, 54);
  terrain.render.coarse_pass = CoarsePass::Auto;
  OpenClOptions options;
  options.purpose = KernelPurpose::DepthSteps;
  const RenderStats by_default = render_opencl(terrain, options).stats;
  const RenderStats with_cone = render_opencl(with_cones(terrain), options).stats;
  EXPECT_GT(by_default.coarse_steps, 0u);
  EXPECT_EQ(by_default.steps, with_cone.steps);
}

// Bad values through the real executable: one line naming the file position or --set, exit 2,
// no image.
TEST(ConePass, BadValuesAreOneLineErrors) {
  testing::TempDir dir;
  const std::string scene = (dir / "scene.yaml").string();
  const std::string image = (dir / "out.png").string();
  std::ofstream(scene) << "sdf: {sphere: {}}\nrender: {width: 8, height: 8}\n";
  testing::CommandResult r = testing::run_clmarch({"render", scene, "--set", "render.coarse_pass=beam", "-o", image});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("render.coarse_pass"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("none, cone"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(--set)"), std::string::npos) << r.err;

  std::ofstream(scene)
      << "sdf: {sphere: {}}\nrender: {width: 8, height: 8, coarse_pass: cone}\ntiling: {cell: [2, 2, 2]}\n";
  r = testing::run_clmarch({"render", scene, "-o", image});
  EXPECT_EQ(r.exit_code, kExitBadInput);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("scene.yaml:2:44: render.coarse_pass: cone does not combine with tiling.method: cells"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
}

}  // namespace
}  // namespace clmarch
