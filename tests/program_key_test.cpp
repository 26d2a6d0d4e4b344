// Programs are keyed by their feature switches and the shape of the scene's code: the numbers a
// frame changes (camera, march limits, shading, lights) reach the device as data and never rebuild
// the program, and the program's #defines are feature switches only.
#include "cl/device_program.hpp"
#include "codegen/kernel_source.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <regex>
#include <utility>
#include <set>
#include <string>

namespace clmarch {
namespace {

// Every shading part, with two lights; the frames below change their numbers only.
const char* const kLit =
    "camera: {position: [0, 1.5, 5], look_at: [0, 0.5, 0]}\n"
    "render: {width: 40, height: 24, max_distance: 30, coarse_pass: cone}\n"
    "sdf:\n  union:\n    - sphere: {center: [0, 0.6, 0], radius: 0.6, reflectivity: 0.3}\n"
    "    - plane: {normal: [0, 1, 0], offset: 0}\n"
    "lights: [{point: {position: [2, 3, 2]}}, {directional: {direction: [-1, 2, 1], intensity: 0.5}}]\n"
    "shading: {model: blinn_phong, specular: 0.4, step_ao: 5000, ambient_occlusion: {}, shadows: {mode: "
    "soft_improved},\n"
    "          reflections: 1, sky: {}, glow: {radius: 0.2}, planetary_glow: {}, fog: {density: 0.02},\n"
    "          height_fog: {density: 0.05}, tone_map: reinhard, gamma: 2.2}\n";

Scene lit(const std::string& yaml = kLit) { return load_scene_text(yaml, "lit.yaml"); }

/// kLit with the first occurrence of each from replaced by its to.
Scene lit_with(std::initializer_list<std::pair<std::string, std::string>> changes) {
  std::string yaml = kLit;
  for (const auto& [from, to] : changes) {
    const std::size_t at = yaml.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) yaml.replace(at, from.size(), to);
  }
  return lit(yaml);
}
Scene lit_with(const std::string& from, const std::string& to) { return lit_with({{from, to}}); }

KernelOptions shaded() { return KernelOptions{KernelPurpose::Shaded, 16}; }

// Each of these changes numbers of MarchParams or the lights buffer, not the program.
TEST(ProgramKey, NumbersOfTheFrameKeepTheProgram) {
  const ProgramKey key = program_key(lit(), shaded());
  const std::pair<const char*, const char*> changes[] = {
      {"position: [0, 1.5, 5]", "position: [0.3, 1.7, 4.5]"},
      {"max_distance: 30", "max_distance: 25, epsilon: 0.002, max_steps: 90"},
      {"position: [2, 3, 2]", "position: [-2, 4, 1], intensity: 2, color: [1, 0.5, 0.5]"},
      {"specular: 0.4", "specular: 0.4, diffuse: 0.8, ambient: [0.2, 0.1, 0.1], background: [0.1, 0.2, 0.3]"},
      {"step_ao: 5000", "step_ao: 3000"},
      {"ambient_occlusion: {}", "ambient_occlusion: {samples: 3, step: 0.08, power: 2}"},
      {"mode: soft_improved", "mode: soft_improved, k: 8, min_t: 0.02, max_t: 12, max_steps: 40"},
      {"reflections: 1", "reflections: 2"},
      {"sky: {}", "sky: {horizon: [1, 0.9, 0.8]}"},
      {"glow: {radius: 0.2}", "glow: {radius: 0.3, color: [0.5, 0.5, 1]}"},
      {"planetary_glow: {}", "planetary_glow: {sharpness: 4, sun_direction: [1, 1, 0]}"},
      {"fog: {density: 0.02}", "fog: {density: 0.05, color: [0.8, 0.8, 0.9]}"},
      {"height_fog: {density: 0.05}", "height_fog: {density: 0.08, falloff: 0.3, sun_power: 4}"},
      {"gamma: 2.2", "gamma: 1.8"},
      {"lights: [", "lights: [{point: {position: [0, 5, 0]}}, {directional: {direction: [1, 1, 0]}}, "},
      {"lights: [{point: {position: [2, 3, 2]}}, ", "lights: ["},
  };
  for (const auto& [from, to] : changes) EXPECT_EQ(program_key(lit_with(from, to), shaded()), key) << to;
}

// What changes the code does change the key: a feature switch, a spelled literal, a shape.
TEST(ProgramKey, FeaturesLiteralsAndShapesMakeAnotherProgram) {
  const ProgramKey key = program_key(lit(), shaded());
  const std::pair<const char*, const char*> changes[] = {
      {"planetary_glow: {}, fog: {density: 0.02},", "planetary_glow: {},"},
      {"mode: soft_improved", "mode: hard"},
      {"model: blinn_phong", "model: phong"},
      {"gamma: 2.2", "gamma: 1"},
      {"radius: 0.6", "radius: 0.7"},
      // The scene's specular and shininess are its nodes' defaults: literals of map_color.
      {"specular: 0.4", "specular: 0.7"},
      {"- plane: {normal: [0, 1, 0], offset: 0}", "- box: {half_size: [3, 0.1, 3]}"},
  };
  for (const auto& [from, to] : changes)
    EXPECT_NE(program_key(lit_with(from, to), shaded()), key) << from << " -> " << to;
  KernelOptions depth{KernelPurpose::DepthSteps, 16};
  EXPECT_NE(program_key(lit(), depth), key);
  KernelOptions slots = shaded();
  slots.value_slots = {0};
  EXPECT_NE(program_key(lit(), slots), key) << "a literal read from the values is no longer spelled";
}

// Comments spell numbers for the reader (an operand grid's cells, the map frame's origin) that
// change no program: two frames of a grid whose cells differ share one.
TEST(ProgramKey, CommentsAreNoPartOfTheShape) {
  EXPECT_EQ(code_shape("vfloat d = 1; /* 12 cells */ return d; /* end */"), "vfloat d = 1;  return d; ");
  const auto spheres = [](double spacing) {
    std::string yaml = "render: {pruning: grid}\nsdf:\n  union:\n";
    for (int i = 0; i < 60; ++i)
      yaml += fmt::format("    - sphere: {{center: [{}, 0, 0], radius: 0.2}}\n", spacing * i);
    return testing::scene_from_yaml(yaml);
  };
  const Scene near = spheres(0.5), far = spheres(1.5);
  const KernelOptions options = shaded();
  ASSERT_NE(march_scene_code(near).source, march_scene_code(far).source) << "the grid's comment names its cells";
  EXPECT_EQ(program_key(near, options), program_key(far, options));
}

// A renderer made for one frame renders the next, whose numbers all differ and which has a light
// more (the lights buffer grows), then one light fewer, each as a renderer of its own would: plane
// for plane, at 1 and 16 lanes.
TEST(ProgramKey, OneRendererDrawsEachFrameAsItsOwnWould) {
  const Scene frames[] = {
      lit(),
      lit_with({{"position: [0, 1.5, 5]", "position: [0.4, 1.6, 4.8]"},
                {"lights: [", "lights: [{point: {position: [0, 5, 0], intensity: 0.7}}, "},
                {"fog: {density: 0.02}", "fog: {density: 0.04}"},
                {"specular: 0.4", "specular: 0.4, ambient: [0.15, 0.1, 0.1]"}}),
      lit_with("lights: [{point: {position: [2, 3, 2]}}, ", "lights: ["),
  };
  for (int lanes : {1, 16}) {
    OpenClOptions options;
    options.lanes = lanes;
    OpenClRenderer renderer(frames[0], options);
    for (const Scene& frame : frames) {
      ASSERT_TRUE(renderer.can_render(frame, options));
      renderer.set_scene(frame);
      const FrameBuffers shared = renderer.render().buffers;
      const FrameBuffers own = render_opencl(frame, options).buffers;
      for (int c = 0; c < kChannelCount; ++c) {
        EXPECT_EQ(shared.planes[c], own.planes[c])
            << kChannelNames[c] << " lanes " << lanes << " lights " << frame.lights.size();
      }
    }
  }
}

// render.literals: buffer reads every number of the tree from the values buffer, so that scenes
// differing in their numbers alone (positions, radii, angles, blend radii, colours, materials) share
// one program keyed by the tree's shape, and each renders as its own program with spelled literals
// would (issue 41: a value edit without a rebuild). auto and inline spell them.
const char* const kEdited =
    "camera: {position: [0, 1.5, 5], look_at: [0, 0.5, 0]}\n"
    "render: {width: 40, height: 24, max_distance: 30, literals: LITERALS}\n"
    "sdf:\n  smooth_union:\n    k: 0.3\n    children:\n"
    "      - sphere: {center: [0, 0.6, 0], radius: 0.6173, color: [0.9, 0.2, 0.1], specular: 0.3}\n"
    "      - box: {center: [0.8, 0.4, 0], half_size: [0.3, 0.4, 0.3], rotate: [0, 30, 0]}\n"
    "      - plane: {normal: [0, 1, 0], offset: 0}\n"
    "lights: [{point: {position: [2, 3, 2]}}]\n";

Scene edited(const std::string& literals, std::initializer_list<std::pair<std::string, std::string>> changes = {}) {
  std::string yaml = kEdited;
  yaml.replace(yaml.find("LITERALS"), 8, literals);
  for (const auto& [from, to] : changes) {
    const std::size_t at = yaml.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) yaml.replace(at, from.size(), to);
  }
  return load_scene_text(yaml, "edited.yaml");
}

const std::initializer_list<std::pair<std::string, std::string>> kValueEdits = {
    {"radius: 0.6173", "radius: 0.45"},
    {"k: 0.3", "k: 0.15"},
    {"rotate: [0, 30, 0]", "rotate: [10, 75, 0]"},
    {"color: [0.9, 0.2, 0.1]", "color: [0.1, 0.5, 0.9]"},
    {"specular: 0.3", "specular: 0.7"},
    {"center: [0.8, 0.4, 0]", "center: [0.7, 0.5, -0.2]"}};

TEST(LiteralPlacement, BufferKeysProgramsByTheTreesShape) {
  const KernelOptions options = shaded();
  const ProgramKey inline_key = program_key(edited("inline"), options);
  EXPECT_EQ(edited("auto").render.literals, LiteralPlacement::Auto);
  EXPECT_EQ(program_key(edited("auto"), options), inline_key) << "auto spells the literals";
  EXPECT_NE(program_key(edited("inline", kValueEdits), options), inline_key);

  OpenClOptions cl;
  OpenClRenderer renderer(edited("buffer"), cl);
  EXPECT_EQ(renderer.render().stats.literals, "buffer");
  EXPECT_EQ(renderer.source().find("0.6173"), std::string::npos) << "a number of the tree is spelled";
  EXPECT_NE(renderer.source().find("values[0]"), std::string::npos);
  const Scene changed = edited("buffer", kValueEdits);
  ASSERT_TRUE(renderer.can_render(changed, cl)) << "a value edit needs a new program";
  EXPECT_FALSE(renderer.can_render(
      edited("buffer", {{"- plane:", "- torus: {major_radius: 2, minor_radius: 0.1}\n      - plane:"}}), cl))
      << "another shape is another program";
  renderer.set_scene(changed);
  const RenderResult shared = renderer.render();
  EXPECT_EQ(shared.stats.build_ms, 0.0) << "the edit re-rendered from the built program";
  const RenderResult spelled = render_opencl(edited("inline", kValueEdits), cl);
  EXPECT_EQ(spelled.stats.literals, "inline");
  // The same arithmetic on the same floats, read instead of spelled: the compiler may still fuse or
  // fold differently around a known constant, so depths agree to float rounding, not bit for bit.
  const std::vector<float>& depth = shared.buffers.plane(Channel::Depth);
  const std::vector<float>& expected = spelled.buffers.plane(Channel::Depth);
  ASSERT_EQ(depth.size(), expected.size());
  int hits = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) {
    ASSERT_EQ(std::isinf(depth[i]), std::isinf(expected[i])) << "pixel " << i;
    if (std::isinf(depth[i])) continue;
    ++hits;
    EXPECT_NEAR(depth[i], expected[i], 1e-4f + 1e-5f * expected[i]) << "pixel " << i;
  }
  EXPECT_GT(hits, static_cast<int>(depth.size()) / 2);
  for (Channel c : {Channel::R, Channel::G, Channel::B}) {
    const std::vector<float>& got = shared.buffers.plane(c);
    const std::vector<float>& want = spelled.buffers.plane(c);
    for (std::size_t i = 0; i < got.size(); ++i) ASSERT_NEAR(got[i], want[i], 2e-3f) << "pixel " << i;
  }
}

TEST(LiteralPlacement, TheKeyTakesAutoInlineOrBufferAndStatsSayWhich) {
  EXPECT_EQ(testing::error_of("render: {literals: spelled}\nsdf: {sphere: {}}\n"),
            "s.yaml:1:20: render.literals must be one of auto, inline, buffer (got 'spelled')");
  testing::TempDir dir;
  const std::string scene = (dir / "s.yaml").string();
  {
    std::ofstream out(scene);
    out << "render: {width: 16, height: 8}\nsdf: {sphere: {radius: 0.8}}\n";
  }
  for (const char* placement : {"inline", "buffer"}) {
    const auto result = testing::run_clmarch(
        {"render", scene, "--no-image", "--stats", "--set", std::string("render.literals=") + placement});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find(fmt::format("\"literals\":\"{}\"", placement)), std::string::npos) << result.out;
  }
}

// A value edit in a new process: the program read from the driver's cache, not compiled again.
TEST(LiteralPlacement, AnEditInTheNextProcessLoadsTheCachedProgram) {
  testing::TempDir dir;
  const std::string scene = (dir / "s.yaml").string();
  const auto render = [&](const char* radius) {
    return testing::run_clmarch({"render", scene, "--no-image", "--stats", "--verbose", "--set",
                                 "render.literals=buffer", "--set", std::string("sdf.sphere.radius=") + radius},
                                {"POCL_CACHE_DIR=" + (dir / "cache").string()});
  };
  {
    std::ofstream out(scene);
    out << "render: {width: 16, height: 8}\nsdf: {sphere: {radius: 0.8}}\n";
  }
  const auto first = render("0.8");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  if (first.err.find("driver cache miss") == std::string::npos) GTEST_SKIP() << "not PoCL: " << first.err;
  const auto second = render("0.55");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.err.find("driver cache hit"), std::string::npos) << second.err;
}

// The program's #defines switch features; numbers reach it as MarchParams and the lights. The only
// defines with a value are the packet's shape (LANES, PACKETS_PER_ITEM) and the shadow mode, named.
TEST(KernelSource, DefinesAreFeatureSwitches) {
  const std::string source = generate_kernel_source(lit(), shaded());
  const std::string header = source.substr(0, source.find("#line 1"));
  const std::regex define(R"(#define (\w+)( (.*))?)");
  std::set<std::string> names;
  for (std::sregex_iterator it(header.begin(), header.end(), define), end; it != end; ++it) {
    const std::string name = (*it)[1].str(), value = (*it)[3].str();
    names.insert(name);
    if (name == "LANES" || name == "PACKETS_PER_ITEM") {
      EXPECT_TRUE(std::regex_match(value, std::regex(R"(\d+)"))) << name << " " << value;
    } else if (name == "SHADOW_MODE") {
      EXPECT_EQ(value, "CLMARCH_SHADOW_SOFT_IMPROVED");
    } else {
      EXPECT_EQ(value, "") << name;
    }
  }
  for (const char* feature :
       {"NEED_SHADING", "SHADING_MODEL_BLINN_PHONG", "SHADOW_MODE", "AMBIENT_OCCLUSION", "REFLECTIONS", "STEP_AO",
        "FOG", "SKY", "GLOW", "PLANET_GLOW", "HEIGHT_FOG", "TONE_MAP_REINHARD", "DISPLAY_GAMMA", "COARSE_PASS"}) {
    EXPECT_EQ(names.count(feature), 1u) << feature;
  }
}

}  // namespace
}  // namespace clmarch

namespace clmarch {
namespace {

// A process builds each program once: tests, frames and sweeps that render the same program share
// it (issue 46), and a different source or option set is a program of its own.
TEST(DevicePrograms, AProcessBuildsTheSameSourceOnce) {
  const DeviceEntry device = select_device(std::nullopt);
  const std::string source =
      fmt::format("/* DevicePrograms {} */ kernel void fill(global float* x) {{ x[0] = 1.0f; }}\n",
                  std::chrono::steady_clock::now().time_since_epoch().count());
  const DeviceProgram first = build_device_program(device, source);
  const DeviceProgram second = build_device_program(device, source);
  EXPECT_EQ(first.program(), second.program());
  EXPECT_EQ(first.context(), second.context());
  EXPECT_EQ(second.build_ms, 0.0);
  const DeviceProgram fast =
      build_device_program(device, source, std::string(kBuildOptions) + " -cl-fast-relaxed-math");
  EXPECT_NE(fast.program(), first.program());
  EXPECT_EQ(fast.context(), first.context()) << "one context per device";
  forget_device_programs();
  const DeviceProgram rebuilt = build_device_program(device, source);
  EXPECT_NE(rebuilt.program(), first.program());
  cl::Kernel kernel(rebuilt.program, "fill");
  cl::Buffer out(rebuilt.context, CL_MEM_WRITE_ONLY, sizeof(float));
  kernel.setArg(0, out);
  rebuilt.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(1));
  float value = 0.0f;
  rebuilt.queue.enqueueReadBuffer(out, CL_TRUE, 0, sizeof(float), &value);
  EXPECT_EQ(value, 1.0f);
}

}  // namespace
}  // namespace clmarch
