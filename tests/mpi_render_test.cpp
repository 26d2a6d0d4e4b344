// clmarch render under mpirun: the frames of an animation and the tiles of one image, rendered by
// three ranks, are bit for bit one process's output; a rank that fails ends the run non-zero with
// its message; an interrupted run leaves only complete files. Skipped when MPI was not built in.
// Three ranks share the test machine's 2 cores (--oversubscribe), so the renders are small.
#include "cli/render_tiles.hpp"
#include "support/child_process.hpp"
#include "support/sanitizers.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>
#include <thread>

namespace clmarch {
namespace {

using namespace std::chrono_literals;
using testing::ClmarchProcess;
using testing::CommandResult;
using testing::TempDir;

#if CLMARCH_HAVE_MPI
constexpr const char* kMpiexec = CLMARCH_MPIEXEC;
#else
constexpr const char* kMpiexec = "";
#endif

/// mpirun's environment. CI runs as root, which Open MPI refuses unless told. Under the sanitizers
/// Open MPI would unload its components (mca_*.so) at MPI_Finalize, and its libraries keep no
/// frame pointers: the ranks keep the components loaded and unwind allocations fully, so that
/// the leak suppressions for Open MPI (tests/sanitize/sanitizer_defaults.cpp) see where its
/// allocations come from.
std::vector<std::string> mpirun_environment() {
  std::vector<std::string> environment = {"OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"};
#if defined(CLMARCH_UNDER_ASAN)
  environment.push_back("OMPI_MCA_mca_base_component_disable_dlclose=1");
  environment.push_back("LSAN_OPTIONS=fast_unwind_on_malloc=0");
#endif
  return environment;
}
const std::vector<std::string> kMpirunEnvironment = mpirun_environment();

/// mpirun's environment for a run that fails by design (a rank without a driver, a signal): its
/// exit code is not 0 whatever LeakSanitizer finds, so the ranks skip the leak check, which under
/// the sanitizers took 20 of such a test's 24 s (killed ranks scanned PoCL's heap) and could not
/// fail it.
std::vector<std::string> failing_run_environment() {
  std::vector<std::string> environment = kMpirunEnvironment;
#if defined(CLMARCH_UNDER_ASAN)
  environment.push_back("ASAN_OPTIONS=detect_leaks=0");
#endif
  return environment;
}

/// mpirun -n ranks on this machine, however few its cores.
std::vector<std::string> mpirun(int ranks) { return {kMpiexec, "--oversubscribe", "-n", std::to_string(ranks)}; }

/// Runs clmarch args on ranks ranks and waits (at most two minutes).
CommandResult run_under_mpirun(int ranks, const std::vector<std::string>& args) {
  ClmarchProcess process(args, kMpirunEnvironment, false, mpirun(ranks));
  CommandResult result;
  result.exit_code = process.wait(120s).value_or(-1);
  result.out = process.out();
  result.err = process.err();
  return result;
}

/// The JSON lines of --stats.
std::vector<nlohmann::json> json_lines(const std::string& out) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

/// The file's pixels, every channel (float for EXR), for a bitwise comparison.
std::vector<float> pixels_of(const std::filesystem::path& path) { return testing::read_image(path).pixels; }

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Tiles start where a band may (a multiple of 8 rows), and an image has about eight a rank.
TEST(MpiTiles, RowsAreWholeBandsAboutEightTilesARank) {
  for (int height : {1, 7, 8, 90, 720, 2160, 65536}) {
    for (int ranks : {1, 2, 3, 16, 1000}) {
      const int rows = tile_rows_for(height, ranks);
      EXPECT_EQ(rows % kBandRowAlignment, 0) << height << " rows, " << ranks << " ranks";
      EXPECT_GE(rows, kBandRowAlignment);
      const int tiles = (height + rows - 1) / rows;
      if (height >= 8 * kBandRowAlignment * ranks) {
        EXPECT_GE(tiles, 8 * ranks) << height << " rows, " << ranks << " ranks";
      }
    }
  }
  EXPECT_EQ(tile_rows_for(720, 3), 24);
}

#define SKIP_WITHOUT_MPI() \
  if (std::string(kMpiexec).empty()) GTEST_SKIP() << "clmarch was built without MPI"

TEST(MpiRender, FramesEqualOneProcesssFrames) {
  SKIP_WITHOUT_MPI();
  TempDir one, many;
  const std::string scene = testing::source_path("scenes/moving_shapes.yaml").string();
  const auto args = [&](const TempDir& dir) {
    return std::vector<std::string>{"render",    scene,
                                    "--size",    "160x90",
                                    "--frames",  "0:7",
                                    "-o",        (dir / "f_####.png").string(),
                                    "--buffers", (dir / "b_####.exr").string(),
                                    "--stats"};
  };
  const CommandResult single = testing::run_clmarch(args(one));
  ASSERT_EQ(single.exit_code, 0) << single.err;
  const CommandResult distributed = run_under_mpirun(3, args(many));
  ASSERT_EQ(distributed.exit_code, 0) << distributed.err;
  ASSERT_EQ(many.files(), one.files());
  EXPECT_EQ(many.files().size(), 16u);
  for (const std::string& name : one.files()) {
    EXPECT_TRUE(same_bits(pixels_of(one / name), pixels_of(many / name))) << name;
  }
  // Each rank prints the --stats lines of its own frames, with its rank and host.
  std::set<int> frames;
  for (const nlohmann::json& line : json_lines(distributed.out)) {
    EXPECT_TRUE(line.contains("rank") && line.contains("host")) << line;
    frames.insert(line.at("frame").get<int>());
  }
  EXPECT_EQ(frames, (std::set<int>{0, 1, 2, 3, 4, 5, 6, 7})) << distributed.out;
}

TEST(MpiRender, TilesOfOneImageEqualOneProcesssImage) {
  SKIP_WITHOUT_MPI();
  TempDir one, many;
  const std::string scene = testing::source_path("scenes/moving_shapes.yaml").string();
  const auto args = [&](const TempDir& dir) {
    return std::vector<std::string>{"render",    scene,
                                    "--size",    "1280x720",
                                    "--time",    "0.7",
                                    "-o",        (dir / "image.png").string(),
                                    "--buffers", (dir / "buffers.exr").string()};
  };
  const CommandResult single = testing::run_clmarch(args(one));
  ASSERT_EQ(single.exit_code, 0) << single.err;
  const CommandResult distributed = run_under_mpirun(3, args(many));
  ASSERT_EQ(distributed.exit_code, 0) << distributed.err;
  ASSERT_EQ(many.files(), one.files());
  for (const char* name : {"image.png", "buffers.exr"}) {
    EXPECT_TRUE(same_bits(pixels_of(one / name), pixels_of(many / name))) << name;
  }
}

// --stats under MPI: rank 0 prints one line per rank for an image, whose steps add up to one
// process's.
TEST(MpiRender, StatsOfAnImageHaveALinePerRank) {
  SKIP_WITHOUT_MPI();
  TempDir dir;
  const std::string scene = testing::source_path("scenes/torus.yaml").string();
  const std::vector<std::string> args = {"render", scene, "--size", "160x120", "-o", (dir / "t.png").string(),
                                         "--stats"};
  const CommandResult single = testing::run_clmarch(args);
  ASSERT_EQ(single.exit_code, 0) << single.err;
  const CommandResult distributed = run_under_mpirun(2, args);
  ASSERT_EQ(distributed.exit_code, 0) << distributed.err;
  const std::vector<nlohmann::json> lines = json_lines(distributed.out);
  ASSERT_EQ(lines.size(), 2u) << distributed.out;
  std::uint64_t steps = 0;
  int tiles = 0;
  for (int rank = 0; rank < 2; ++rank) {
    EXPECT_EQ(lines[rank].at("rank"), rank);
    EXPECT_EQ(lines[rank].at("ranks"), 2);
    steps += lines[rank].at("steps").get<std::uint64_t>();
    tiles += lines[rank].at("tiles").get<int>();
  }
  EXPECT_EQ(steps, json_lines(single.out).at(0).at("steps").get<std::uint64_t>());
  EXPECT_EQ(tiles, 15) << "120 rows over 2 ranks: about 8 tiles a rank, of 8 rows at least";
}

// A rank whose device fails (here: no OpenCL driver at all for rank 1) stops the run: its own
// message names it, its host and its frame; rank 0 says which rank failed; the exit code is not 0;
// the frames written are whole.
TEST(MpiRender, AFailingRankEndsTheRunWithItsMessage) {
  SKIP_WITHOUT_MPI();
  TempDir dir, no_drivers;
  const std::string scene = testing::source_path("scenes/moving_shapes.yaml").string();
  const std::vector<std::string> args = {"render",   scene, "--size", "96x54",
                                         "--frames", "0:7", "-o",     (dir / "f_####.png").string()};
  // Rank 1 is another program context of mpirun: clmarch run by env with an empty driver folder.
  std::vector<std::string> command = {kMpiexec, "--oversubscribe", "-n", "1", CLMARCH_BINARY};
  command.insert(command.end(), args.begin(), args.end());
  command.insert(command.end(),
                 {":", "-n", "1", "/usr/bin/env", "OCL_ICD_VENDORS=" + no_drivers.path().string(), CLMARCH_BINARY});
  command.insert(command.end(), args.begin(), args.end());
  command.insert(command.end(), {":", "-n", "1"});
  // The last context's program is the one ClmarchProcess appends.
  ClmarchProcess process(args, failing_run_environment(), false, command);
  const std::optional<int> code = process.wait(120s);
  ASSERT_TRUE(code.has_value()) << process.err();
  EXPECT_NE(*code, 0) << process.err();
  const std::string err = process.err();
  EXPECT_NE(err.find("clmarch: rank 1 on "), std::string::npos) << err;
  EXPECT_NE(err.find(", frame "), std::string::npos) << err;
  EXPECT_NE(err.find("no OpenCL platform or device found"), std::string::npos) << err;
  EXPECT_NE(err.find("failed at frame"), std::string::npos) << "rank 0's summary\n" << err;
  for (const std::string& name : dir.files()) {
    EXPECT_NE(name.front(), '.') << "a temporary file was left: " << name;
    EXPECT_EQ(testing::read_image(dir / name).width, 96) << name;
  }
}

// Ctrl-C to mpirun (which passes SIGTERM to every rank) stops the run: the frames done stay, the
// ones in progress leave nothing, not even a temporary file.
TEST(MpiRender, AnInterruptedRunLeavesOnlyCompleteFiles) {
  SKIP_WITHOUT_MPI();
  TempDir dir;
  const std::string scene = testing::source_path("scenes/moving_shapes.yaml").string();
  ClmarchProcess process({"render", scene, "--size", "320x180", "--frames", "0:199", "-o",
                          (dir / "f_####.png").string(), "--buffers", (dir / "b_####.exr").string()},
                         failing_run_environment(), false, mpirun(3));
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  while (dir.files().size() < 4 && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(20ms);
  ASSERT_GE(dir.files().size(), 4u) << process.err();
  process.send_signal(SIGINT);
  const std::optional<int> code = process.wait(60s);
  ASSERT_TRUE(code.has_value()) << "mpirun did not stop\n" << process.err();
  EXPECT_NE(*code, 0);
  const std::vector<std::string> files = dir.files();
  EXPECT_LT(files.size(), 400u) << "stopped before the end";
  for (const std::string& name : files) {
    ASSERT_NE(name.front(), '.') << "a temporary file was left: " << name;
    EXPECT_EQ(testing::read_image(dir / name).width, 320) << name;
  }
}

}  // namespace
}  // namespace clmarch
