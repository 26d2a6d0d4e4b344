// What a shader author meets in a first hour (issue 29): runs without a color image, --set KEY=null,
// colors given as 0..255, the help of --fps, and check's report saying what decides it.
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace clmarch {
namespace {

using testing::run_clmarch;
using testing::TempDir;

const std::string kBallScene =
    "sdf: {sphere: {radius: 1}}\nrender: {width: 16, height: 8}\nlights: [{directional: {direction: [0, 1, 1]}}]\n";

// --dump-kernel alone, run where the scene lies, writes the kernel and nothing else (no SCENE.png
// over a tracked file); with -o it renders too.
TEST(FirstHour, DumpKernelAloneWritesOnlyTheKernel) {
  TempDir dir;
  std::ofstream(dir / "ball.yaml") << kBallScene;
  const std::string command =
      "cd '" + dir.path().string() + "' && '" + CLMARCH_BINARY + "' render ball.yaml --dump-kernel k.cl 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"ball.yaml", "k.cl"}));
  std::ifstream kernel(dir / "k.cl");
  const std::string source((std::istreambuf_iterator<char>(kernel)), std::istreambuf_iterator<char>());
  EXPECT_NE(source.find("__kernel void march"), std::string::npos);
  const auto both = run_clmarch({"render", (dir / "ball.yaml").string(), "--dump-kernel", (dir / "k2.cl").string(),
                                 "-o", (dir / "ball.png").string()});
  ASSERT_EQ(both.exit_code, 0) << both.err;
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"ball.png", "ball.yaml", "k.cl", "k2.cl"}));
}

// --no-image: the buffers alone, or the --stats line alone.
TEST(FirstHour, NoImageWritesBuffersOrStatsOnly) {
  TempDir dir;
  std::ofstream(dir / "ball.yaml") << kBallScene;
  const auto buffers =
      run_clmarch({"render", (dir / "ball.yaml").string(), "--no-image", "--buffers", (dir / "b.exr").string()});
  ASSERT_EQ(buffers.exit_code, 0) << buffers.err;
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"b.exr", "ball.yaml"}));
  const std::string command =
      "cd '" + dir.path().string() + "' && '" + CLMARCH_BINARY + "' render ball.yaml --no-image --stats 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  for (char buffer[512]; std::fgets(buffer, sizeof buffer, pipe);) out += buffer;
  ASSERT_EQ(pclose(pipe), 0);
  EXPECT_NE(out.find("\"rays_per_s\""), std::string::npos) << out;
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"b.exr", "ball.yaml"}));
}

// --set KEY=null removes an optional key: the shadows go, and the image changes.
TEST(FirstHour, SetNullRemovesAKey) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml")
      << "sdf:\n  union:\n    - sphere: {center: [0, 1, 0], radius: 0.5}\n"
         "    - plane: {normal: [0, 1, 0], offset: 0}\n"
         "camera: {position: [0, 2, 4], look_at: [0, 0.5, 0]}\nrender: {width: 32, height: 18}\n"
         "lights: [{directional: {direction: [0.3, 1, 0.2]}}]\nshading: {shadows: {mode: hard}}\n";
  const auto with =
      run_clmarch({"render", (dir / "scene.yaml").string(), "--no-image", "--dump-kernel", (dir / "a.cl").string()});
  const auto without = run_clmarch({"render", (dir / "scene.yaml").string(), "--set", "shading.shadows=null",
                                    "--no-image", "--dump-kernel", (dir / "b.cl").string()});
  ASSERT_EQ(with.exit_code, 0) << with.err;
  ASSERT_EQ(without.exit_code, 0) << without.err;
  std::ifstream a(dir / "a.cl"), b(dir / "b.cl");
  const std::string shadowed((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  const std::string plain((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
  EXPECT_NE(shadowed.find("#define SHADOW_MODE"), std::string::npos);
  EXPECT_EQ(plain.find("#define SHADOW_MODE"), std::string::npos);
  const auto item =
      run_clmarch({"render", (dir / "scene.yaml").string(), "--set", "lights.0=null", "--no-image", "--stats"});
  EXPECT_EQ(item.exit_code, 0) << "a list item can go too: " << item.err;
}

// A color of 0..255 renders, with one warning naming the key; 10 is still plausible light.
TEST(FirstHour, ColorsPastTenWarnOnceNamingTheKey) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml")
      << "sdf:\n  union:\n    - sphere: {radius: 1, color: [255, 0, 0]}\n"
         "    - box: {center: [2, 0, 0], color: [10, 10, 10]}\nrender: {width: 16, height: 8}\n";
  const auto result =
      run_clmarch({"render", (dir / "scene.yaml").string(), "--frames", "0:2", "-o", (dir / "f_#.png").string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string expected = "sdf.union[0].sphere.color has a channel above 10";
  EXPECT_NE(result.err.find(expected), std::string::npos) << result.err;
  EXPECT_EQ(result.err.find(expected), result.err.rfind(expected)) << "once over the three frames:\n" << result.err;
  EXPECT_EQ(result.err.find("union[1]"), std::string::npos) << result.err;
}

// The help line of --fps reads as a sentence (CLI11's "Needs: --frames" used to cut into it).
TEST(FirstHour, FpsHelpReadsWhole) {
  const auto result = run_clmarch({"render", "--help"});
  ASSERT_EQ(result.exit_code, 0);
  const std::size_t at = result.out.find("  --fps ");
  ASSERT_NE(at, std::string::npos);
  const std::string line = result.out.substr(at, result.out.find('\n', at) - at);
  EXPECT_EQ(line.find("Needs"), std::string::npos) << line;
  EXPECT_NE(line.find("Frames per second of --frames"), std::string::npos) << line;
}

// Each line of check's report that decides it says PASS or FAIL and its limit; the misses line
// counts misses.
TEST(FirstHour, CheckMarksWhatDecides) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kBallScene;
  const auto result = run_clmarch({"check", (dir / "scene.yaml").string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  for (const char* line :
       {"PASS non-finite", "PASS hit-mask mismatch", "PASS depth / tolerance p99", "PASS steps difference",
        "PASS normal angle p99", "PASS normal tolerance", "PASS color of hits", "PASS color of misses",
        "misses compared)", "PASS shading", "PASS id mismatch", "check passed"}) {
    EXPECT_NE(result.out.find(line), std::string::npos) << line << " in:\n" << result.out;
  }
  EXPECT_EQ(result.out.find("hits and misses"), std::string::npos) << result.out;
}

}  // namespace
}  // namespace clmarch
