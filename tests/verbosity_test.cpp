// --quiet, --verbose and the progress line: what a render says on stderr, and when.
#include "cl/device_program.hpp"
#include "cl/devices.hpp"
#include "common/errors.hpp"
#include "common/log.hpp"
#include "support/child_process.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

namespace clmarch {
namespace {

using testing::run_clmarch;
using testing::run_clmarch_on_terminal;
using testing::TempDir;

const std::string kSmallScene = "sdf: {sphere: {radius: 1}}\nrender: {width: 16, height: 8}\n";

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Settings given in the scene are named without "(auto)"; the floor is unbounded, and the cone pass
// with step-count occlusion only when asked for.
TEST(Verbosity, VerboseNamesTheMarchSettingsInForce) {
  TempDir dir;
  std::ofstream(dir / "s.yaml") << "sdf: {plane: {}}\ncamera: {position: [0, 1, 3]}\nrender: {width: 8, height: 8}\n"
                                   "shading: {step_ao: 1000}\n";
  const auto run = [&](const std::vector<std::string>& sets) {
    std::vector<std::string> args = {"--verbose", "render", (dir / "s.yaml").string(), "-o", (dir / "o.png").string()};
    for (const std::string& set : sets) args.insert(args.end(), {"--set", set});
    const auto result = run_clmarch(args);
    EXPECT_EQ(result.exit_code, kExitOk) << result.err;
    return result.err;
  };
  const std::string automatic = run({});
  EXPECT_TRUE(contains(
      automatic, "clmarch: march: from the camera (unbounded), coarse pass none (auto), over-relaxation 1 (auto)\n"))
      << automatic;
  const std::string given = run({"render.coarse_pass=cone", "render.over_relaxation=1.5"});
  EXPECT_TRUE(contains(given, "clmarch: march: from the camera (unbounded), coarse pass cone, over-relaxation 1.5\n"))
      << given;
  const std::string tiled = run({"tiling={cell: [4, 4, 4]}"});
  EXPECT_TRUE(contains(
      tiled, "clmarch: march: through the cells of the tiling, coarse pass none (auto), over-relaxation 1 (auto)\n"))
      << tiled;
}

TEST(Verbosity, NormalSaysWhatItWrote) {
  TempDir dir;
  std::ofstream(dir / "s.yaml") << kSmallScene;
  const auto result = run_clmarch({"render", (dir / "s.yaml").string(), "-o", (dir / "o.png").string()});
  ASSERT_EQ(result.exit_code, kExitOk) << result.err;
  EXPECT_EQ(result.err, "clmarch: wrote " + (dir / "o.png").string() + "\n");
}

TEST(Verbosity, QuietSaysNothingBeforeOrAfterTheCommand) {
  TempDir dir;
  std::ofstream(dir / "s.yaml") << kSmallScene;
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--quiet", "render", (dir / "s.yaml").string(), "-o", (dir / "a.png").string()},
        {"render", (dir / "s.yaml").string(), "-q", "-o", (dir / "b.png").string(), "--stats"}}) {
    const auto result = run_clmarch(args);
    ASSERT_EQ(result.exit_code, kExitOk) << result.err;
    EXPECT_EQ(result.err, "");
  }
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"a.png", "b.png", "s.yaml"}));
  // Errors still speak.
  const auto failed = run_clmarch({"--quiet", "render", (dir / "none.yaml").string()});
  EXPECT_EQ(failed.exit_code, kExitBadInput);
  EXPECT_TRUE(contains(failed.err, "cannot read")) << failed.err;
}

TEST(Verbosity, QuietAndVerboseExcludeEachOther) {
  const auto result = run_clmarch({"--quiet", "--verbose", "devices"});
  EXPECT_EQ(result.exit_code, kExitBadInput);
  EXPECT_TRUE(contains(result.err, "--quiet excludes --verbose")) << result.err;
}

TEST(Verbosity, VerboseNamesDeviceBuildLanesLocalSizeAndCache) {
  TempDir dir;
  TempDir cache;
  std::ofstream(dir / "s.yaml") << kSmallScene;
  const DeviceEntry device = select_device(std::nullopt);
  const std::vector<std::string> args = {"--verbose", "render", (dir / "s.yaml").string(), "--lanes",
                                         "4",         "-o",     (dir / "o.png").string()};
  const std::vector<std::string> environment = {"POCL_CACHE_DIR=" + cache.path().string()};
  const auto first = run_clmarch(args, environment);
  ASSERT_EQ(first.exit_code, kExitOk) << first.err;
  EXPECT_TRUE(contains(first.err, "clmarch: device " + device.label() + ", CPU, build options '-cl-std=CL1.2'\n"))
      << first.err;
  EXPECT_TRUE(contains(first.err, "clmarch: lanes 4 (pixels per work-item), local size " +
                                      std::to_string(default_local_size(device)) + ", stages inline, 1 chunk, kernel "))
      << first.err;
  EXPECT_TRUE(contains(first.err, "clmarch: wrote ")) << first.err;
  // What the automatic march settings chose: a lone sphere, bounded, needs no cone pass.
  EXPECT_TRUE(contains(first.err, "clmarch: march: inside a bounding sphere of radius 1")) << first.err;
  EXPECT_TRUE(contains(first.err, ", coarse pass none (auto), over-relaxation 1.2 (auto)\n")) << first.err;
  if (device.platform_name != "Portable Computing Language") GTEST_SKIP() << "the cache is only known for PoCL";
  // An empty cache folder: the first build compiles, the second finds it.
  EXPECT_TRUE(contains(first.err, "driver cache miss (" + cache.path().string() + ")")) << first.err;
  const auto second = run_clmarch(args, environment);
  ASSERT_EQ(second.exit_code, kExitOk) << second.err;
  EXPECT_TRUE(contains(second.err, "driver cache hit (" + cache.path().string() + ")")) << second.err;
  const auto off = run_clmarch(args, {"POCL_CACHE_DIR=" + cache.path().string(), "POCL_KERNEL_CACHE=0"});
  EXPECT_TRUE(contains(off.err, "driver cache off")) << off.err;
}

TEST(Verbosity, VerboseShowsTheWarningsOfASuccessfulBuildVerbatim) {
  const DeviceEntry device = select_device(std::nullopt);
  // A source no driver cache holds: NVIDIA's gives an empty log when its cache serves a build.
  const auto source = [](int build) {
    return fmt::format(
        "#pragma clang diagnostic ignored \"-Wclmarch-test-warning\"\n/* {} {} */\n"
        "kernel void fill(global float* x) {{ x[0] = 1.0f; }}\n",
        std::chrono::steady_clock::now().time_since_epoch().count(), build);
  };
  const Verbosity before = verbosity();
  set_verbosity(Verbosity::Normal);
  ::testing::internal::CaptureStderr();
  build_device_program(device, source(1));
  const std::string normal = ::testing::internal::GetCapturedStderr();
  set_verbosity(Verbosity::Verbose);
  ::testing::internal::CaptureStderr();
  const DeviceProgram program = build_device_program(device, source(2));
  const std::string verbose = ::testing::internal::GetCapturedStderr();
  set_verbosity(before);
  ASSERT_TRUE(contains(program.build_log, "clmarch-test-warning")) << program.build_log;
  EXPECT_FALSE(contains(normal, "build log")) << normal;
  EXPECT_TRUE(contains(verbose, "clmarch: build log of " + device.name + ":\n")) << verbose;
  EXPECT_TRUE(contains(verbose, "clmarch-test-warning")) << "the compiler's own words must follow:\n" << verbose;
}

TEST(Verbosity, ProgressOnlyOnATerminalAndNotWhenQuiet) {
  TempDir dir;
  // Grazing rays that march to max_steps: ~3 s of reference rows alone on a quiet 2-vCPU machine
  // (0.7 s at 256x256 was too close to the 1 s after which the line appears), more beside the
  // piped run.
  std::ofstream(dir / "s.yaml") << "camera: {position: [0, 0.01, 0], look_at: [0, 0.01, -1], fov: 1}\n"
                                   "render: {width: 512, height: 512, max_steps: 1000, max_distance: 1.0e6}\n"
                                   "sdf: {plane: {normal: [0, 1, 0]}}\n";
  const auto args = [&](const std::string& output, bool quiet) {
    std::vector<std::string> a = {"render", (dir / "s.yaml").string(), "--backend", "reference",
                                  "-o",     (dir / output).string()};
    if (quiet) a.push_back("--quiet");
    return a;
  };
  // Not a terminal: no progress, only the result. It runs beside the terminal run to save time.
  testing::ClmarchProcess piped(args("piped.png", false));
  const auto shown = run_clmarch_on_terminal(args("shown.png", false));
  ASSERT_EQ(shown.exit_code, kExitOk) << shown.err;
  EXPECT_TRUE(contains(shown.err, "\r\033[Kreference rows: ")) << shown.err;
  EXPECT_TRUE(contains(shown.err, " rays/s, ")) << shown.err;
  EXPECT_TRUE(contains(shown.err, " s left")) << shown.err;
  EXPECT_TRUE(contains(shown.err, "clmarch: wrote")) << shown.err;
  ASSERT_EQ(piped.wait(std::chrono::seconds(60)), kExitOk) << piped.err();
  EXPECT_EQ(piped.err(), "clmarch: wrote " + (dir / "piped.png").string() + "\n");
  const auto quiet = run_clmarch_on_terminal(args("quiet.png", true));
  ASSERT_EQ(quiet.exit_code, kExitOk) << quiet.err;
  EXPECT_EQ(quiet.err, "");
}

}  // namespace
}  // namespace clmarch
