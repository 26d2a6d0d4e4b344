// Output that cannot be written: refused before rendering when the folder takes no files, and
// when the write itself fails after the render (here: a file size limit, which binds root too),
// exit code 4 and no partial file.
#include "common/errors.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

namespace clmarch {
namespace {

using testing::run_clmarch;
using testing::run_clmarch_in_shell;
using testing::source_path;
using testing::TempDir;

TEST(OutputFailure, FolderThatTakesNoFilesIsRefusedBeforeRendering) {
  const auto result = run_clmarch(
      {"render", source_path("scenes/torus.yaml").string(), "--size", "16x9", "-o", "/proc/clmarch-test.png"});
  EXPECT_EQ(result.exit_code, kExitBadInput) << result.err;
  EXPECT_EQ(result.err.find("--output /proc/clmarch-test.png: "), 0u) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

TEST(OutputFailure, WriteFailingHalfwayLeavesNoPartialFile) {
  TempDir dir;
  // 8 blocks of 512 bytes: the shaded 256x256 float EXR (768 KB before compression) fails well
  // into its pixel data. SIGXFSZ is ignored so that the write returns EFBIG instead of killing.
  const auto result = run_clmarch_in_shell(
      "trap '' XFSZ; ulimit -f 8; ", {"render", source_path("scenes/torus.yaml").string(), "--backend", "reference",
                                      "--size", "256x256", "-o", (dir / "out.exr").string()});
  EXPECT_EQ(result.exit_code, kExitOutputFailed) << result.err;
  EXPECT_EQ(result.err.find((dir / "out.exr").string() + ": cannot write: "), 0u) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(dir.files(), std::vector<std::string>{}) << "the temporary file must be gone";
}

// The 128x72 PNG takes about 2 KB, so a limit of one block falls in the encoder's last buffer,
// whose failed flush at close OpenImageIO does not report: the file must still count as failed.
// Without `trap '' XFSZ` the signal would kill the process, leaving its temporary file; clmarch
// ignores it itself.
TEST(OutputFailure, LimitInTheLastBufferFailsTooWithOrWithoutTheSignalIgnored) {
  for (const char* shell_prefix : {"trap '' XFSZ; ulimit -f 1; ", "ulimit -f 1; "}) {
    TempDir dir;
    const auto result =
        run_clmarch_in_shell(shell_prefix, {"render", source_path("scenes/torus.yaml").string(), "--backend",
                                            "reference", "--size", "128x72", "-o", (dir / "out.png").string()});
    EXPECT_EQ(result.exit_code, kExitOutputFailed) << shell_prefix << result.err;
    EXPECT_EQ(result.err, (dir / "out.png").string() + ": cannot write: File too large\n") << shell_prefix;
    EXPECT_EQ(dir.files(), std::vector<std::string>{}) << shell_prefix << "no partial file, no temporary file";
  }
}

// The 128x72 PNG (about 2 KB) fits in a limit of 40 blocks, the float EXR of all buffers (300 KB
// before compression) does not: both files are written before either replaces its target, so the
// old image stays too.
TEST(OutputFailure, BuffersThatFailLeaveTheOldImageAsItWas) {
  TempDir dir;
  std::ofstream(dir / "out.png") << "the previous image";
  const auto result = run_clmarch_in_shell(
      "ulimit -f 40; ", {"render", source_path("scenes/torus.yaml").string(), "--backend", "reference", "--size",
                         "128x72", "-o", (dir / "out.png").string(), "--buffers", (dir / "out.exr").string()});
  EXPECT_EQ(result.exit_code, kExitOutputFailed) << result.err;
  EXPECT_EQ(result.err, (dir / "out.exr").string() + ": cannot write: File too large\n");
  EXPECT_EQ(dir.files(), std::vector<std::string>{"out.png"}) << "no buffers, no temporary files";
  EXPECT_EQ(testing::read_text(dir / "out.png"), "the previous image");
}

}  // namespace
}  // namespace clmarch
