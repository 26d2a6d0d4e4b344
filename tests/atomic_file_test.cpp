// write_atomically and StagedFiles: the targets appear whole or not at all, whatever stops the
// writes, and files staged together replace their targets only when all of them were written.
#include "common/atomic_file.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace clmarch {
namespace {

using testing::TempDir;

/// The file's text (a name of its own: an unqualified read() in a unity batch would find it before POSIX read).
std::string read_whole_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

using testing::CancellationReset;

TEST(AtomicFile, WritesThroughATemporaryFileInTheSameFolder) {
  TempDir dir;
  std::vector<std::string> during;
  write_atomically(dir / "out.txt", [&](const std::filesystem::path& temp) {
    std::ofstream(temp) << "new";
    during = dir.files();
  });
  ASSERT_EQ(during.size(), 1u);
  EXPECT_TRUE(during[0].starts_with(".out.clmarch-") && during[0].ends_with(".txt")) << during[0];
  EXPECT_EQ(dir.files(), std::vector<std::string>{"out.txt"});
  EXPECT_EQ(read_whole_file(dir / "out.txt"), "new");
}

// A target name at the folder's limit of 255 characters: the temporary name, which adds a dot and
// ".clmarch-PID", cuts the stem instead of failing after the render.
TEST(AtomicFile, TargetNameAtTheLimitStillGetsATemporaryName) {
  TempDir dir;
  const std::string name = std::string(251, 'n') + ".png";
  std::string temporary;
  write_atomically(dir / name, [&](const std::filesystem::path& temp) {
    temporary = temp.filename().string();
    std::ofstream(temp) << "new";
  });
  EXPECT_LE(temporary.size(), 255u) << temporary;
  EXPECT_TRUE(temporary.ends_with(".png")) << temporary;
  EXPECT_EQ(dir.files(), std::vector<std::string>{name});
}

TEST(AtomicFile, FailedWriteLeavesTheOldFileAndNoTemporary) {
  TempDir dir;
  std::ofstream(dir / "out.txt") << "old";
  EXPECT_THROW(write_atomically(dir / "out.txt",
                                [&](const std::filesystem::path& temp) {
                                  std::ofstream(temp) << "half";
                                  throw OutputError("disk full");
                                }),
               OutputError);
  EXPECT_EQ(dir.files(), std::vector<std::string>{"out.txt"});
  EXPECT_EQ(read_whole_file(dir / "out.txt"), "old");
}

TEST(AtomicFile, CtrlCDuringTheWriteRenamesNothing) {
  TempDir dir;
  std::ofstream(dir / "out.txt") << "old";
  const CancellationReset reset;
  EXPECT_THROW(write_atomically(dir / "out.txt",
                                [&](const std::filesystem::path& temp) {
                                  std::ofstream(temp) << "complete, but the user asked to stop";
                                  cancellation_requested().store(true);
                                }),
               Cancelled);
  EXPECT_EQ(dir.files(), std::vector<std::string>{"out.txt"});
  EXPECT_EQ(read_whole_file(dir / "out.txt"), "old");
}

TEST(AtomicFile, OutputFolderMustTakeNewFiles) {
  TempDir dir;
  EXPECT_NO_THROW(check_output_folder(dir / "out.png", "-o"));
  EXPECT_EQ(dir.files(), std::vector<std::string>{}) << "the probe file must be gone";
  // /proc passes access(W_OK) for root, but nobody can create a file there.
  try {
    check_output_folder("/proc/out.png", "--output");
    ADD_FAILURE() << "no error for /proc";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("--output /proc/out.png: "), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("/proc"), std::string::npos) << e.what();
  }
}

TEST(StagedFiles, NoTargetChangesUntilEveryFileIsWritten) {
  TempDir dir;
  std::ofstream(dir / "a.txt") << "old a";
  std::ofstream(dir / "b.txt") << "old b";
  {
    StagedFiles files;
    files.stage(dir / "a.txt", [](const std::filesystem::path& temp) { std::ofstream(temp) << "new a"; });
    EXPECT_THROW(files.stage(dir / "b.txt",
                             [](const std::filesystem::path& temp) {
                               std::ofstream(temp) << "half of b";
                               throw OutputError("disk full");
                             }),
                 OutputError);
    EXPECT_EQ(read_whole_file(dir / "a.txt"), "old a") << "a is written but not in place";
  }
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"a.txt", "b.txt"})) << "no temporary file stays";
  EXPECT_EQ(read_whole_file(dir / "a.txt"), "old a");
  EXPECT_EQ(read_whole_file(dir / "b.txt"), "old b");

  StagedFiles files;
  files.stage(dir / "a.txt", [](const std::filesystem::path& temp) { std::ofstream(temp) << "new a"; });
  files.stage(dir / "b.txt", [](const std::filesystem::path& temp) { std::ofstream(temp) << "new b"; });
  EXPECT_EQ(dir.files().size(), 4u) << "two targets, two temporaries";
  files.commit();
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"a.txt", "b.txt"}));
  EXPECT_EQ(read_whole_file(dir / "a.txt"), "new a");
  EXPECT_EQ(read_whole_file(dir / "b.txt"), "new b");
}

TEST(StagedFiles, ATargetThatBecameAFolderRenamesNothing) {
  TempDir dir;
  std::ofstream(dir / "a.txt") << "old a";
  {
    StagedFiles files;
    files.stage(dir / "a.txt", [](const std::filesystem::path& temp) { std::ofstream(temp) << "new a"; });
    files.stage(dir / "b.txt", [](const std::filesystem::path& temp) { std::ofstream(temp) << "new b"; });
    std::filesystem::create_directory(dir / "b.txt");  // after the checks before the render
    try {
      files.commit();
      FAIL() << "a folder in b's place must fail the commit";
    } catch (const OutputError& e) {
      EXPECT_EQ(std::string(e.what()), (dir / "b.txt").string() + ": cannot write: is a folder");
    }
  }
  EXPECT_EQ(read_whole_file(dir / "a.txt"), "old a") << "a is not replaced when b cannot be";
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"a.txt", "b.txt"})) << "no temporary file stays";
}

TEST(StagedFiles, CtrlCBeforeTheCommitRenamesNothing) {
  TempDir dir;
  std::ofstream(dir / "a.txt") << "old a";
  const CancellationReset reset;
  {
    StagedFiles files;
    files.stage(dir / "a.txt", [](const std::filesystem::path& temp) { std::ofstream(temp) << "new a"; });
    files.stage(dir / "b.txt", [](const std::filesystem::path& temp) { std::ofstream(temp) << "new b"; });
    cancellation_requested().store(true);
    EXPECT_THROW(files.commit(), Cancelled);
  }
  EXPECT_EQ(dir.files(), std::vector<std::string>{"a.txt"});
  EXPECT_EQ(read_whole_file(dir / "a.txt"), "old a");
}

}  // namespace
}  // namespace clmarch
