// Ctrl-C and SIGTERM through the real executable: the render stops at once while it waits on the
// OpenCL device (a build, a chunk) or on a FIFO, and otherwise at its next chunk or reference row;
// nothing is written (no image, no temporary file), one line says so, and the exit code is
// 128 + signal. These tests run serially (tests/CMakeLists.txt): they time how fast a render stops.
#include "cli/interrupts.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "common/pending_file.hpp"
#include "support/child_process.hpp"
#include "support/test_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include <sys/stat.h>
#include <unistd.h>

namespace clmarch {
namespace {

using namespace std::chrono_literals;
using testing::ClmarchProcess;
using testing::TempDir;

// Rays nearly parallel to a plane (a field of view of 0.001 degrees): each step advances by the
// camera's height, so every ray marches until max_steps and a render costs width x height x
// max_steps, whatever the device.
constexpr const char* kGrazingScene = R"(
camera: {position: [0, 0.01, 0], look_at: [0, 0.01, -1], fov: 0.001}
render: {max_distance: 1.0e6}
sdf: {plane: {normal: [0, 1, 0], offset: 0}}
)";

struct Interrupted {
  int exit_code = -1;
  /// From the signal to the "interrupted" line (the process's teardown after it is not counted:
  /// under the sanitizers, freeing and leak-checking a GB of buffers takes a while).
  double seconds_to_stop = 0.0;
  std::string err;
};

/// Starts clmarch with args, waits for ready_line on stderr, sends signal, waits for the exit.
Interrupted interrupt(const std::vector<std::string>& args, const std::string& ready_line, int signal,
                      const std::vector<std::string>& environment = {}) {
  ClmarchProcess process(args, environment);
  Interrupted result;
  if (!process.wait_for_stderr(ready_line, 120s)) {
    ADD_FAILURE() << "never printed '" << ready_line << "':\n" << process.err();
    return result;
  }
  const auto sent = std::chrono::steady_clock::now();
  process.send_signal(signal);
  process.wait_for_stderr("clmarch: interrupted", 30s);
  result.seconds_to_stop = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  const std::optional<int> code = process.wait(30s);
  result.err = process.err();
  if (!code) {
    ADD_FAILURE() << "still running 30 s after the signal:\n" << result.err;
    return result;
  }
  result.exit_code = *code;
  return result;
}

/// A union of 400 spheres with a radius no earlier run used, so that PoCL's cache cannot serve its
/// build: on 2 cores the build takes 2-5 s, and the first dispatch as long again (PoCL compiles the
/// kernel for its work-group size then).
std::string slow_to_build_scene() {
  // One of 10^5 radii, and a sphere out of view at one of 10^6 depths: 10^11 programs, each built
  // once at most.
  std::random_device random;
  const double radius = 0.25 + static_cast<double>(random() % 100000) * 1e-6;
  const int depth = 10 + static_cast<int>(random() % 1000000);
  std::string yaml = fmt::format(
      "camera: {{position: [200, 0, 300], look_at: [200, 0, -5]}}\nsdf:\n  union:\n"
      "    - {{sphere: {{center: [0, -{}, 0], radius: 1}}}}\n",
      depth);
  for (int i = 0; i < 400; ++i)
    yaml += fmt::format("    - {{sphere: {{center: [{}, 0, -5], radius: {}}}}}\n", i, radius);
  return yaml;
}

std::vector<std::string> slow_render_args(const TempDir& dir) {
  std::ofstream(dir / "scene.yaml") << slow_to_build_scene();
  return {"--verbose", "render", (dir / "scene.yaml").string(), "--size", "64x36", "-o", (dir / "out.png").string()};
}

TEST(Interrupt, FirstSignalDuringTheProgramBuildExitsAtOnce) {
  TempDir dir;
  const Interrupted r = interrupt(slow_render_args(dir), "build options", SIGINT);
  EXPECT_EQ(r.exit_code, kExitInterrupted) << r.err;
  EXPECT_TRUE(r.err.ends_with("\nclmarch: interrupted\n")) << r.err;
  EXPECT_EQ(r.err.find("clmarch: build "), std::string::npos) << "the build ran to its end\n" << r.err;
  EXPECT_LT(r.seconds_to_stop, 1.0) << "a build of this scene takes seconds";
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"});
}

TEST(Interrupt, FirstSignalWhileTheFirstDispatchCompilesExitsAtOnce) {
  TempDir dir;
  const Interrupted r = interrupt(slow_render_args(dir), "clmarch: build ", SIGTERM);
  EXPECT_EQ(r.exit_code, 143) << r.err;
  EXPECT_TRUE(r.err.ends_with("\nclmarch: interrupted\n")) << r.err;
  EXPECT_LT(r.seconds_to_stop, 1.0) << "PoCL's compile at the first dispatch of this scene takes seconds";
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"});
}

/// Whether signal is in the mask field of /proc/PID/status ("SigBlk": blocked by the main thread,
/// "SigCgt": caught by a handler), a hexadecimal mask of bit signal - 1.
bool in_signal_mask(pid_t pid, const std::string& field, int signal) {
  std::ifstream status(fmt::format("/proc/{}/status", pid));
  for (std::string line; std::getline(status, line);) {
    if (line.starts_with(field + ":"))
      return (std::stoull(line.substr(field.size() + 1), nullptr, 16) >> (signal - 1)) & 1U;
  }
  return false;
}

TEST(Interrupt, FirstSignalWhileOpeningAFifoNobodyWritesExitsAtOnce) {
  TempDir dir;
  ASSERT_EQ(mkfifo((dir / "scene.yaml").c_str(), 0600), 0);
  ClmarchProcess process({"render", (dir / "scene.yaml").string(), "-o", (dir / "out.png").string()});
  // The process prints nothing before it blocks in open(): wait for its handler, then a little.
  for (int i = 0; i < 2000 && !in_signal_mask(process.pid(), "SigCgt", SIGINT); ++i) std::this_thread::sleep_for(5ms);
  std::this_thread::sleep_for(200ms);
  process.send_signal(SIGINT);
  const std::optional<int> code = process.wait(10s);
  ASSERT_TRUE(code) << "still waiting for a writer 10 s after the signal";
  EXPECT_EQ(*code, kExitInterrupted) << process.err();
  EXPECT_EQ(process.err(), "clmarch: interrupted\n");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"});
}

TEST(Interrupt, AnInheritedIgnoredSigintStaysIgnoredThroughTheBuild) {
  TempDir dir;
  // As `clmarch ... &` in a script. PoCL's compiler puts its own SIGINT handler in place of the
  // ignored disposition (to remove its temporary files, failing the build); blocked, it never runs.
  ClmarchProcess process(slow_render_args(dir), {}, /*sigint_ignored=*/true);
  ASSERT_TRUE(process.wait_for_stderr("build options", 120s)) << process.err();
  EXPECT_TRUE(in_signal_mask(process.pid(), "SigBlk", SIGINT));
  for (int i = 0; i < 5; ++i) {
    process.send_signal(SIGINT);
    std::this_thread::sleep_for(100ms);
  }
  const std::optional<int> code = process.wait(300s);
  ASSERT_TRUE(code) << process.err();
  EXPECT_EQ(*code, kExitOk) << process.err();
  EXPECT_NE(process.err().find("clmarch: wrote"), std::string::npos) << process.err();
}

TEST(Interrupt, OpenClRenderStopsAtTheNextChunkAndWritesNothing) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kGrazingScene;
  // 4096x6144 pixels are 6 chunks of 4 M pixels (the renderer's most per dispatch), ~0.5 s each on
  // PoCL with 2 cores: an uninterrupted render runs 3 s more after the build, plus its writes.
  const Interrupted r =
      interrupt({"--verbose", "render", (dir / "scene.yaml").string(), "--size", "4096x6144", "--set",
                 "render.max_steps=300", "-o", (dir / "out.png").string(), "--buffers", (dir / "buffers.exr").string()},
                "clmarch: build ", SIGINT);
  EXPECT_EQ(r.exit_code, kExitInterrupted) << r.err;
  EXPECT_TRUE(r.err.ends_with("\nclmarch: interrupted\n")) << r.err;
  EXPECT_EQ(r.err.find("wrote"), std::string::npos) << r.err;
  EXPECT_LT(r.seconds_to_stop, 2.0) << "the signal came before the first chunk; one chunk takes ~0.7 s";
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"}) << "no image, no buffers, no temporary file";
}

// clmarch mesh (issue 44) stops at a signal too and leaves no file: the Mandelbulb at 1024 cells
// samples for tens of seconds on 2 cores after its program is built; the signal comes once it is.
TEST(Interrupt, MeshStopsAndWritesNothing) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << testing::read_text(testing::source_path("scenes/mandelbulb.yaml"));
  const Interrupted r = interrupt(
      {"--verbose", "mesh", (dir / "scene.yaml").string(), "--resolution", "1024", "-o", (dir / "bulb.ply").string()},
      "clmarch: build ", SIGINT);
  EXPECT_EQ(r.exit_code, kExitInterrupted) << r.err;
  EXPECT_TRUE(r.err.ends_with("\nclmarch: interrupted\n")) << r.err;
  EXPECT_EQ(r.err.find("wrote"), std::string::npos) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"}) << "no mesh, no temporary file";
}

// The signal lands while the host allocates the image's planes (0.7 s for 4096x6144), before the
// first chunk's wait; the coarse cone pass is enqueued by then, and with an empty PoCL cache PoCL
// compiles it for its work-group size on its own threads. The process must leave with its exit
// code, not crash in PoCL's compiler as exit()'s destructors tear LLVM down (it did: a segfault or
// "LLVM ERROR" after "clmarch: interrupted", six times in six).
TEST(Interrupt, ASignalWhileTheDriverStillCompilesLeavesWithItsExitCode) {
  TempDir dir;
  TempDir empty_cache;
  std::ofstream(dir / "scene.yaml") << kGrazingScene;
  const Interrupted r = interrupt({"--verbose", "render", (dir / "scene.yaml").string(), "--size", "4096x6144", "--set",
                                   "render.max_steps=300", "-o", (dir / "out.png").string()},
                                  "clmarch: build ", SIGINT, {"POCL_CACHE_DIR=" + empty_cache.path().string()});
  EXPECT_NE(r.err.find("coarse pass cone"), std::string::npos) << "the cone pass is what is compiling\n" << r.err;
  EXPECT_EQ(r.exit_code, kExitInterrupted) << r.err;
  EXPECT_TRUE(r.err.ends_with("\nclmarch: interrupted\n")) << r.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"});
}

TEST(Interrupt, ReferenceRenderStopsWithinARow) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kGrazingScene;
  // 256 rows of 32 pixels of 1e5 steps each: 128 rows a core. A row's time is this build's and
  // this machine's (0.2 s in a release build, up to 3 s with the sanitizers on the 2-vCPU EPYC,
  // where a fixed bound of 3 s failed), so it is measured: a render of two rows, one a core, whole
  // process. Stopping may take the row each core is in, then the process's exit: at most twice
  // that render, plus a second for the machine's noise, against 128 rows for the whole image.
  const std::vector<std::string> row_args = {"render",    (dir / "scene.yaml").string(),
                                             "--backend", "reference",
                                             "--size",    "32x2",
                                             "--set",     "render.max_steps=100000",
                                             "-o",        (dir / "row.png").string()};
  const auto started = std::chrono::steady_clock::now();
  const testing::CommandResult row = testing::run_clmarch(row_args);
  const double row_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  ASSERT_EQ(row.exit_code, 0) << row.err;
  std::filesystem::remove(dir / "row.png");
  const double bound = 2.0 * row_seconds + 1.0;
  ASSERT_LT(bound, 0.25 * 128 * row_seconds) << "the whole image must take far longer than stopping may";
  const std::vector<std::string> args = {"--verbose",
                                         "render",
                                         (dir / "scene.yaml").string(),
                                         "--backend",
                                         "reference",
                                         "--size",
                                         "32x256",
                                         "--set",
                                         "render.max_steps=100000",
                                         "-o",
                                         (dir / "out.png").string()};
  const Interrupted r = interrupt(args, "rendering on the CPU reference", SIGINT);
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_TRUE(r.err.ends_with("\nclmarch: interrupted\n")) << r.err;
  EXPECT_LT(r.seconds_to_stop, bound) << "two rows rendered in " << row_seconds << " s";
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"});

  const Interrupted term = interrupt(args, "rendering on the CPU reference", SIGTERM);
  EXPECT_EQ(term.exit_code, 143) << "128 + SIGTERM\n" << term.err;
  EXPECT_TRUE(term.err.ends_with("\nclmarch: interrupted\n")) << term.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"});
}

TEST(Interrupt, SecondSignalExitsAtOnceAndRemovesTheFilesBeingWritten) {
  TempDir dir;
  // An image and its buffers are both written before either is renamed into place.
  const std::filesystem::path image = dir / ".out.clmarch-1.png";
  const std::filesystem::path buffers = dir / ".out.clmarch-1.exr";
  std::ofstream(image) << "an image";
  std::ofstream(buffers) << "half the buffers";
  EXPECT_EXIT(
      {
        install_interrupt_handlers();
        const PendingFile pending_image(image);
        const PendingFile pending_buffers(buffers);
        std::raise(SIGINT);
        // The first signal only asks to stop.
        if (!cancellation_requested().load()) std::_Exit(1);
        std::raise(SIGINT);
        std::_Exit(2);
      },
      ::testing::ExitedWithCode(130), "");
  EXPECT_EQ(dir.files(), std::vector<std::string>{});
}

}  // namespace
}  // namespace clmarch
