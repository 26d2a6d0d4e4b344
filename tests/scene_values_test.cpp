// Animated literals as program inputs: the frames of an animation whose distance functions differ
// only in values share one program, which reads those values from its scene_values buffer, and
// each frame renders exactly as the program that spells its values would.
#include "codegen/cl_literals.hpp"
#include "codegen/kernel_source.hpp"
#include "codegen/varying_literals.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <regex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace clmarch {
namespace {

// A sphere that moves and breathes, a box that spins, a torus that grows (at t = 0 its scale is 1,
// and an unscaled node is another shape of code) and a floor: shadows, occlusion, a mirror and the
// cone pass all evaluate the distance function, so each reads the values; and a background, an
// ambient light and a fog that change, which the shading and the misses read from MarchParams.
const char* const kAnimated =
    "camera: {position: [0, 2, 6], look_at: [0, 0, 0]}\n"
    "render: {width: 45, height: 27, coarse_pass: cone}\n"
    "sdf:\n"
    "  union:\n"
    "    - sphere: {center: [\"cos(t)\", 0, 0], radius: \"0.5 + 0.1 * sin(3 * t)\", color: [\"0.5 + 0.4 * sin(t)\", "
    "0.3, 0.2]}\n"
    "    - box: {half_size: [0.4, 0.4, 0.4], translate: [-1.5, 0, 0], rotate: [0, \"40 * t\", 0], reflectivity: 0.4}\n"
    "    - torus: {center: [1.5, 0, 0], major_radius: 0.5, minor_radius: 0.15, scale: \"1 + 0.2 * sin(t)\"}\n"
    "    - plane: {normal: [0, 1, 0], offset: 0.7}\n"
    "lights: [{point: {position: [2, 4, 3]}}]\n"
    "shading: {shadows: {mode: soft}, ambient_occlusion: {}, reflections: 1, background: [\"0.2 + 0.1 * sin(t)\", 0.3, "
    "0.4],\n"
    "          ambient: \"0.1 + 0.05 * cos(t)\", fog: {density: \"0.05 + 0.02 * sin(t)\", color: [0.5, 0.5, 0.6]}}\n";

Scene frame_at(double t, const std::string& yaml = kAnimated) { return load_scene_text(yaml, "animated.yaml", {}, t); }

/// The source with every values[j] replaced by the literal spelling of values[j].
std::string with_values_spelled(const std::string& source, const std::vector<float>& values) {
  static const std::regex slot(R"(values\[(\d+)\])");
  std::string out;
  auto at = source.cbegin();
  for (std::sregex_iterator it(source.begin(), source.end(), slot), end; it != end; ++it) {
    out.append(at, (*it)[0].first);
    out += cl_float(values.at(std::stoul((*it)[1].str())));
    at = (*it)[0].second;
  }
  out.append(at, source.cend());
  return out;
}

TEST(SdfCode, EverySlotReadsTheLiteralItReplaces) {
  VaryingLiterals varying;
  for (double t : {0.3, 0.8}) varying.add(frame_at(t));
  const Scene frame = frame_at(0.55);
  const ValueSlots slots = varying.slots_for(frame);
  ASSERT_FALSE(slots.empty());
  const SdfCode code = march_scene_code(frame);
  const std::string spelled = spell_sdf_code(code);
  EXPECT_EQ(spelled.find('@'), std::string::npos);
  EXPECT_FALSE(std::regex_search(spelled, std::regex(R"(values\[\d)")));
  const std::string with_slots = spell_sdf_code(code, slots);
  std::string body = with_slots.substr(with_slots.find("*/\n") + 3);  // past the values[0 .. n] comment
  EXPECT_EQ(with_values_spelled(body, slot_values(code, slots).joined()), spelled);
  // Numbered as the source reads them.
  EXPECT_NE(body.find("values[0]"), std::string::npos);
  EXPECT_LT(body.find("values[0]"), body.find("values[1]"));
}

// Only what depends on t varies, in map and map_color alike: the sphere's centre x and radius, the
// four entries of the box's matrix that a rotation about y changes (the other five are 0 or 1 at
// every angle), the torus's three inverse scales, the scale of its distance, the x of its pivot
// (its bound's centre, 1.5 scale, rounded to float) and its centre's x from that pivot (what the
// rounding left); in map_color the sphere's red. The shading's numbers are no literals of the code:
// they reach the program in MarchParams.shading.
TEST(VaryingLiterals, OnlyWhatTheTimeChangesVaries) {
  VaryingLiterals varying;
  for (double t : {0.2, 0.7, 1.1}) varying.add(frame_at(t));
  const Scene frame = frame_at(0.2);
  const std::vector<float> values = slot_values(march_scene_code(frame), varying.slots_for(frame)).joined();
  const auto count = [&](double v) { return std::count(values.begin(), values.end(), static_cast<float>(v)); };
  EXPECT_EQ(values.size(), 2u * (2u + 4u + 3u + 1u + 2u) + 1u);
  EXPECT_EQ(count(std::cos(0.2)), 2);
  EXPECT_EQ(count(0.5 + 0.1 * std::sin(0.6)), 2);
  EXPECT_EQ(count(0.5 + 0.4 * std::sin(0.2)), 1);
  EXPECT_EQ(count(1.0 + 0.2 * std::sin(0.2)), 2);
  EXPECT_EQ(count(1.0 / (1.0 + 0.2 * std::sin(0.2))), 6);
  EXPECT_EQ(count(0.2 + 0.1 * std::sin(0.2)), 0);
  EXPECT_EQ(count(0.1 + 0.05 * std::cos(0.2)), 0);
  EXPECT_EQ(count(0.05 + 0.02 * std::sin(0.2)), 0);
  EXPECT_EQ(count(1.5 * (1.0 + 0.2 * std::sin(0.2))), 2);
}

TEST(VaryingLiterals, AShapeSeenOnceHasNoSlots) {
  VaryingLiterals varying;
  for (double t : {0.0, 0.5, 1.0}) varying.add(frame_at(t));
  EXPECT_TRUE(varying.slots_for(frame_at(0.0)).empty()) << "at t = 0 the torus is not scaled: another shape";
  EXPECT_FALSE(varying.slots_for(frame_at(0.5)).empty());
  EXPECT_TRUE(varying.slots_for(frame_at(0.5, "sdf: {torus: {}}\n")).empty()) << "a shape never added";
  VaryingLiterals still;
  for (double t : {0.5, 1.0}) still.add(frame_at(t, "sdf: {sphere: {radius: 0.5}}\n"));
  EXPECT_TRUE(still.slots_for(frame_at(0.5, "sdf: {sphere: {radius: 0.5}}\n")).empty()) << "nothing moves";
}

TEST(VaryingLiterals, AFrameThatVariesMoreWidensItsShapesSlots) {
  const std::string yaml = "sdf: {sphere: {center: [\"t < 1 ? 0 : t\", 0, 0], radius: \"1 + t\"}}\n";
  VaryingLiterals varying;
  for (double t : {0.25, 0.5}) varying.add(frame_at(t, yaml));
  const std::size_t before = varying.slots_for(frame_at(0.5, yaml)).size();
  const ValueSlots widened = varying.add(frame_at(2.0, yaml));
  EXPECT_EQ(varying.slots_for(frame_at(0.5, yaml)).size(), before + 2) << "the centre's x too, in map and map_color";
  EXPECT_EQ(widened, varying.slots_for(frame_at(0.5, yaml))) << "add returns its shape's slots";
}

TEST(KernelSource, ValueSlotsAreForMarchProgramsAndTheScenesLiterals) {
  const Scene frame = frame_at(0.5);
  KernelOptions eval{KernelPurpose::EvalPoints, 16};
  eval.value_slots = {0};
  EXPECT_THROW(generate_kernel_source(frame, eval), std::invalid_argument);
  KernelOptions march{KernelPurpose::Shaded, 16};
  march.value_slots = {static_cast<int>(march_scene_code(frame).literals.size())};
  EXPECT_THROW(generate_kernel_source(frame, march), std::invalid_argument);
}

// One program renders every frame of the shape: each frame equals the render of the program
// that spells its values, plane for plane.
void expect_one_program_renders_every_frame(const std::string& yaml, const std::vector<double>& times, int lanes,
                                            KernelPurpose purpose) {
  VaryingLiterals varying;
  for (double t : times) varying.add(frame_at(t, yaml));
  OpenClOptions spelled;
  spelled.lanes = lanes;
  spelled.purpose = purpose;
  OpenClOptions shared = spelled;
  shared.value_slots = varying.slots_for(frame_at(times.front(), yaml));
  OpenClRenderer renderer(frame_at(times.front(), yaml), shared);
  EXPECT_NE(renderer.source().find("values[0]"), std::string::npos);
  for (double t : times) {
    const Scene frame = frame_at(t, yaml);
    ASSERT_TRUE(renderer.can_render(frame, shared)) << t;
    renderer.set_scene(frame);
    const FrameBuffers a = renderer.render().buffers;
    const FrameBuffers b = render_opencl(frame, spelled).buffers;
    for (int c = 0; c < kChannelCount; ++c) {
      EXPECT_EQ(a.planes[c], b.planes[c]) << kChannelNames[c] << " t " << t << " lanes " << lanes;
    }
  }
}

// Shaded at 1 and 16 lanes, and depth-only (the cone pass without the shading) at 16.
TEST(SceneValues, OneProgramRendersEveryFrameAsItsOwnProgramWould) {
  const std::vector<double> times = {0.25, 0.6, 1.3};
  for (const auto& [lanes, purpose] : {std::pair{1, KernelPurpose::Shaded}, std::pair{16, KernelPurpose::Shaded},
                                       std::pair{16, KernelPurpose::DepthSteps}}) {
    expect_one_program_renders_every_frame(kAnimated, times, lanes, purpose);
  }
  VaryingLiterals varying;
  for (double t : times) varying.add(frame_at(t));
  OpenClOptions options;
  options.value_slots = varying.slots_for(frame_at(times.front()));
  const OpenClRenderer renderer(frame_at(times.front()), options);
  OpenClOptions unscaled;
  unscaled.value_slots = varying.slots_for(frame_at(0.0));
  EXPECT_FALSE(renderer.can_render(frame_at(0.0), unscaled)) << "the unscaled torus is another program";
}

// Every literal of a scene that uses every shading feature, read from the values instead of
// spelled: the image is the spelled program's, shaded at 1 and 16 lanes and depth-only with the
// cone pass.
TEST(SceneValues, EveryLiteralAsAnInputRendersTheSpelledImage) {
  const Scene scene = load_scene_text(
      "camera: {position: [0, 1.5, 5], look_at: [0, 0.5, 0]}\n"
      "render: {width: 40, height: 24, max_distance: 30, coarse_pass: cone}\n"
      "sdf:\n  union:\n    - sphere: {center: [0, 0.6, 0], radius: 0.6, reflectivity: 0.3, scale: 1.2}\n"
      "    - box: {half_size: [0.3, 0.3, 0.3], translate: [1.2, 0.3, 0], rotate: [0, 25, 0]}\n"
      "    - plane: {normal: [0, 1, 0], offset: 0}\n"
      "lights: [{point: {position: [2, 3, 2]}}, {directional: {direction: [-1, 2, 1], intensity: 0.5}}]\n"
      "shading: {model: blinn_phong, specular: 0.4, step_ao: 5000, ambient_occlusion: {}, shadows: {mode: "
      "soft_improved},\n"
      "          reflections: 1, sky: {}, glow: {radius: 0.2}, planetary_glow: {}, fog: {density: 0.02},\n"
      "          height_fog: {density: 0.05}, tone_map: reinhard, gamma: 2.2}\n",
      "every_feature.yaml");
  ValueSlots every(march_scene_code(scene).literals.size());
  std::iota(every.begin(), every.end(), 0);
  for (const auto& [lanes, purpose] : {std::pair{1, KernelPurpose::Shaded}, std::pair{16, KernelPurpose::Shaded},
                                       std::pair{16, KernelPurpose::DepthSteps}}) {
    OpenClOptions spelled;
    spelled.lanes = lanes;
    spelled.purpose = purpose;
    OpenClOptions inputs = spelled;
    inputs.value_slots = every;
    const RenderResult a = render_opencl(scene, inputs);
    const RenderResult b = render_opencl(scene, spelled);
    for (int c = 0; c < kChannelCount; ++c)
      EXPECT_EQ(a.buffers.planes[c], b.buffers.planes[c]) << kChannelNames[c] << " lanes " << lanes;
  }
  EXPECT_EQ(spell_sdf_code(march_scene_code(scene), every).find('@'), std::string::npos);
}

// The cells tiling's own march (march_cells) and the mod tiling's wrapped field read them too.
TEST(SceneValues, TiledFramesShareOneProgram) {
  const std::string cells =
      "camera: {position: [0.5, 0.15, 0.05], look_at: [3.2, 1.9, 4.1], fov: 60}\n"
      "render: {width: 40, height: 24, max_steps: 400, max_distance: 40}\n"
      "tiling: {cell: [1, 1, 1], method: cells}\n"
      "sdf: {sphere: {center: [0.5, \"0.5 + 0.1 * sin(t)\", 0.5], radius: \"0.25 + 0.05 * cos(t)\"}}\n"
      "lights: [{directional: {direction: [1, 2, 1]}}]\n";
  expect_one_program_renders_every_frame(cells, {0.5, 1.5}, 16, KernelPurpose::Shaded);
  expect_one_program_renders_every_frame(std::regex_replace(cells, std::regex("cells"), "mod"), {0.5, 1.5}, 16,
                                         KernelPurpose::Shaded);
}

}  // namespace
}  // namespace clmarch
