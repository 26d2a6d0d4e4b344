// --frames A:B --fps F: the range and file names, and a sequence rendered through the executable
// whose frames equal single renders at t = n / fps.
#include "cli/frame_sequence.hpp"
#include "common/errors.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace clmarch {
namespace {

using testing::read_image;
using testing::run_clmarch;
using testing::TempDir;

TEST(FrameRange, ParsesInclusiveRangeAndTimes) {
  const FrameRange range = parse_frame_range("3:10", 4.0);
  EXPECT_EQ(range.first, 3);
  EXPECT_EQ(range.last, 10);
  EXPECT_EQ(range.count(), 8);
  EXPECT_DOUBLE_EQ(range.time_of(6), 1.5);
}

TEST(FrameRange, RejectsMalformedRanges) {
  for (const char* text : {"", "3", "3:", ":4", "a:b", "-1:4", "5:4", "1:2:3", "1.5:3", "1234567:1234568"}) {
    EXPECT_THROW(parse_frame_range(text, 24.0), InputError) << text;
  }
  EXPECT_THROW(parse_frame_range("0:1", 0.0), InputError);
  EXPECT_THROW(parse_frame_range("0:1", -24.0), InputError);
}

TEST(FramePath, HashRunBecomesPaddedFrameNumber) {
  const FrameRange range = parse_frame_range("0:120", 24.0);
  EXPECT_EQ(frame_path("out/shot_####.png", 7, range), "out/shot_0007.png");
  EXPECT_EQ(frame_path("f#.exr", 12, range), "f12.exr");
  EXPECT_EQ(frame_path("a#b/f##.png", 3, range), "a#b/f03.png") << "only the file name is numbered";
}

TEST(FramePath, WithoutHashesTheNumberGoesBeforeTheExtension) {
  EXPECT_EQ(frame_path("dir/torus.png", 5, parse_frame_range("0:9", 24.0)), "dir/torus_0005.png");
  EXPECT_EQ(frame_path("torus.png", 5, parse_frame_range("0:123456", 24.0)), "torus_000005.png");
}

TEST(FrameSequence, FramesEqualSingleRendersAtTheirTimes) {
  TempDir dir;
  const std::string scene = testing::source_path("scenes/moving_shapes.yaml").string();
  const auto sequence = run_clmarch({"render", scene, "--size", "48x27", "--frames", "2:3", "--fps", "4", "-o",
                                     (dir / "seq_##.png").string(), "--buffers", (dir / "buf.exr").string()});
  ASSERT_EQ(sequence.exit_code, 0) << sequence.err;
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"buf_0002.exr", "buf_0003.exr", "seq_02.png", "seq_03.png"}));

  for (const auto& [frame, time] : {std::pair{2, "0.5"}, std::pair{3, "0.75"}}) {
    const std::string single = (dir / ("single_" + std::to_string(frame) + ".png")).string();
    const auto one = run_clmarch({"render", scene, "--size", "48x27", "--time", time, "-o", single});
    ASSERT_EQ(one.exit_code, 0) << one.err;
    const auto a = read_image(dir / ("seq_0" + std::to_string(frame) + ".png"));
    const auto b = read_image(single);
    EXPECT_EQ(a.pixels, b.pixels) << "frame " << frame << " must be the render at t = " << time;
  }
  EXPECT_NE(read_image(dir / "seq_02.png").pixels, read_image(dir / "seq_03.png").pixels)
      << "the scene moves between t = 0.5 and 0.75";
}

// A camera that orbits, and a light that follows it, change only the kernel's arguments: every
// frame after the first reuses the first frame's program and buffers (build_ms 0, --dump-kernel
// still written per frame), and each frame is still the single render at its time, buffers and
// all. Shapes that move change literals of the distance function, which the frames' shared
// program reads from its values: in moving_shapes only frame 0 (the sphere's scale exactly 1, no
// rotation) has a code of its own.
TEST(FrameSequence, FramesOfAMovingCameraReuseTheProgram) {
  TempDir dir;
  const std::string scene = (dir / "orbit.yaml").string();
  std::ofstream(scene) << "camera: {position: [\"4 * cos(t)\", 1.5, \"4 * sin(t)\"], look_at: [0, 0, 0]}\n"
                          "render: {width: 40, height: 24}\n"
                          "sdf: {union: [{torus: {}}, {sphere: {center: [1.6, 0, 0], radius: 0.4}}, {plane: {normal: "
                          "[0, 1, 0], offset: 0.6}}]}\n"
                          "lights: [{point: {position: [\"3 * cos(t)\", 3, \"3 * sin(t)\"]}}]\n"
                          "shading: {shadows: {mode: soft}}\n";
  const auto sequence =
      run_clmarch({"render", scene, "--frames", "0:2", "--fps", "2", "--stats", "-o", (dir / "o_#.png").string(),
                   "--buffers", (dir / "b_#.exr").string(), "--dump-kernel", (dir / "k_#.cl").string()});
  ASSERT_EQ(sequence.exit_code, 0) << sequence.err;
  std::istringstream lines(sequence.out);
  std::vector<double> build_ms;
  for (std::string line; std::getline(lines, line);)
    build_ms.push_back(nlohmann::json::parse(line)["build_ms"].get<double>());
  ASSERT_EQ(build_ms.size(), 3u);
  EXPECT_GT(build_ms[0], 0.0);
  EXPECT_EQ(build_ms[1], 0.0);
  EXPECT_EQ(build_ms[2], 0.0);
  for (int frame = 0; frame <= 2; ++frame) {
    const std::string n = std::to_string(frame);
    EXPECT_TRUE(std::filesystem::exists(dir / ("k_" + n + ".cl"))) << frame;
    const std::string time = std::to_string(frame / 2.0);
    const auto one = run_clmarch({"render", scene, "--time", time, "-o", (dir / ("s_" + n + ".png")).string(),
                                  "--buffers", (dir / ("sb_" + n + ".exr")).string()});
    ASSERT_EQ(one.exit_code, 0) << one.err;
    EXPECT_EQ(read_image(dir / ("o_" + n + ".png")).pixels, read_image(dir / ("s_" + n + ".png")).pixels) << frame;
    EXPECT_EQ(read_image(dir / ("b_" + n + ".exr")).pixels, read_image(dir / ("sb_" + n + ".exr")).pixels) << frame;
  }
  EXPECT_NE(read_image(dir / "o_0.png").pixels, read_image(dir / "o_1.png").pixels)
      << "the camera moves around the sphere";

  const auto moving_shapes =
      run_clmarch({"render", testing::source_path("scenes/moving_shapes.yaml").string(), "--size", "32x18", "--frames",
                   "0:3", "--stats", "-o", (dir / "m_#.png").string(), "--dump-kernel", (dir / "m_#.cl").string()});
  ASSERT_EQ(moving_shapes.exit_code, 0) << moving_shapes.err;
  std::istringstream moving_lines(moving_shapes.out);
  std::vector<double> moving_build_ms;
  for (std::string line; std::getline(moving_lines, line);) {
    moving_build_ms.push_back(nlohmann::json::parse(line)["build_ms"].get<double>());
  }
  ASSERT_EQ(moving_build_ms.size(), 4u);
  EXPECT_GT(moving_build_ms[0], 0.0);
  EXPECT_GT(moving_build_ms[1], 0.0);
  EXPECT_EQ(moving_build_ms[2], 0.0);
  EXPECT_EQ(moving_build_ms[3], 0.0);
  EXPECT_EQ(testing::read_text(dir / "m_0.cl").find("values[0]"), std::string::npos) << "frame 0 spells its values";
  EXPECT_NE(testing::read_text(dir / "m_3.cl").find("values[0]"), std::string::npos);
}

TEST(SampleFrames, AllFramesUpToTheLimitElseTheFirstTwoTheLastAndEvenlyBetween) {
  EXPECT_EQ(sample_frames(parse_frame_range("5:9", 24.0), 8), (std::vector<int>{5, 6, 7, 8, 9}));
  EXPECT_EQ(sample_frames(parse_frame_range("5:5", 24.0), 8), (std::vector<int>{5}));
  EXPECT_EQ(sample_frames(parse_frame_range("0:100", 24.0), 6), (std::vector<int>{0, 1, 25, 50, 75, 100}));
  const std::vector<int> many = sample_frames(parse_frame_range("10:999999", 24.0), 64);
  EXPECT_EQ(many.size(), 64u);
  EXPECT_TRUE(std::is_sorted(many.begin(), many.end()));
  EXPECT_EQ(many.front(), 10);
  EXPECT_EQ(many[1], 11);
  EXPECT_EQ(many.back(), 999999);
}

TEST(FrameSequence, BadOptionsWriteNothing) {
  TempDir dir;
  const std::string scene = testing::source_path("scenes/moving_shapes.yaml").string();
  const std::string out = (dir / "f.png").string();
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  for (const Case& c :
       {Case{{"--frames", "4:2"}, "--frames 4:2: the last frame must not come before the first"},
        Case{{"--frames", "0-4"}, "--frames 0-4: expected FIRST:LAST"},
        Case{{"--fps", "30"}, "--fps requires --frames"}, Case{{"--frames", "0:1", "--fps", "0"}, "--fps"},
        Case{{"--frames", "0:1", "--time", "2"}, "--time and --frames both set the time"}}) {
    std::vector<std::string> args = {"render", scene, "--size", "16x9", "-o", out};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const auto result = run_clmarch(args);
    EXPECT_EQ(result.exit_code, kExitBadInput) << c.message;
    EXPECT_NE(result.err.find(c.message), std::string::npos) << result.err;
    EXPECT_TRUE(dir.files().empty()) << c.message;
  }
}

// A scene that breaks at one time fails before any frame is written, on both backends, also at a
// frame between the 64 the OpenCL path compares (frame 121 of 0:200 is t = 5.04 at 24 fps).
TEST(FrameSequence, AFrameThatFailsToLoadStopsTheSequenceBeforeAnyIsWritten) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << "camera: {position: [0, 0, 5]}\n"
                                       "sdf: {sphere: {radius: \"(t > 5.03 && t < 5.05) ? -1 : 1\"}}\n";
  for (const char* backend : {"opencl", "reference"}) {
    const auto result = run_clmarch({"render", (dir / "scene.yaml").string(), "--size", "4x4", "--frames", "0:200",
                                     "--backend", backend, "-q", "-o", (dir / "f_###.png").string()});
    EXPECT_EQ(result.exit_code, kExitBadInput) << backend << ": " << result.err;
    EXPECT_NE(result.err.find("sdf.sphere.radius must be > 0"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("at t = 5.04"), std::string::npos) << result.err;
    EXPECT_EQ(dir.files(), std::vector<std::string>{"scene.yaml"}) << backend;
  }
}

// A frame's numbered file is checked with the options, not when its turn comes: an existing folder
// of a frame's name, a name that numbering makes too long, two options numbered onto one file.
TEST(FrameSequence, AFrameFileThatCannotBeWrittenStopsTheSequenceBeforeAnyIsWritten) {
  TempDir dir;
  std::filesystem::create_directory(dir / "shot_0003.png");
  const std::string scene = testing::source_path("scenes/torus.yaml").string();
  const std::string long_name = std::string(251, 'x') + ".png";
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  for (const Case& c :
       {Case{{"-o", (dir / "shot_####.png").string()}, "/shot_0003.png: is a folder, expected a file name"},
        Case{{"-o", (dir / long_name).string()}, "the file name has 260 characters, more than the 255 a folder takes"},
        Case{{"-o", (dir / "a_####.exr").string(), "--buffers", (dir / "a.exr").string()},
             "--output and --buffers are the same file"}}) {
    std::vector<std::string> args = {"render", scene, "--size", "16x9", "--frames", "0:5"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const auto result = run_clmarch(args);
    EXPECT_EQ(result.exit_code, kExitBadInput) << c.message << "\n" << result.err;
    EXPECT_NE(result.err.find(c.message), std::string::npos) << result.err;
    EXPECT_EQ(dir.files(), std::vector<std::string>{"shot_0003.png"}) << c.message;
  }
}

}  // namespace
}  // namespace clmarch
