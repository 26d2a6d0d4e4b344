// `cmake --install` of this build into a temporary prefix: every file where GNUInstallDirs and the
// shells look for it, every example scene, and the installed clmarch rendering an installed scene
// (with the CPU reference: no OpenCL program to build).
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace clmarch {
namespace {

using testing::run_shell;
using testing::shell_quote;
using testing::TempDir;

namespace fs = std::filesystem;

/// The scene files below folder, relative to it.
std::vector<std::string> scene_files(const fs::path& folder) {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file() && entry.path().extension() == ".yaml")
      files.push_back(fs::relative(entry.path(), folder).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(InstallTree, InstallsEveryFileAndRendersAnInstalledScene) {
  const TempDir prefix;
  const auto install = run_shell(shell_quote(CLMARCH_CMAKE) + " --install " + shell_quote(CLMARCH_BUILD_DIR) +
                                 " --prefix " + shell_quote(prefix.path().string()));
  ASSERT_EQ(install.exit_code, 0) << install.out << install.err;
  // GNUInstallDirs may name lib64 or the like for libraries, but these folders are fixed.
  for (const char* file :
       {"bin/clmarch", "share/man/man1/clmarch.1.gz", "share/bash-completion/completions/clmarch",
        "share/zsh/vendor-completions/_clmarch", "share/fish/vendor_completions.d/clmarch.fish",
        "share/doc/clmarch/LICENSE", "share/doc/clmarch/README.md", "share/doc/clmarch/CHANGELOG.md"}) {
    EXPECT_TRUE(fs::is_regular_file(prefix / file)) << file;
  }
  EXPECT_EQ(scene_files(prefix / "share/clmarch/scenes"), scene_files(testing::source_path("scenes")));
  const auto man = run_shell("gzip -dc " + shell_quote((prefix / "share/man/man1/clmarch.1.gz").string()));
  EXPECT_EQ(man.out, testing::read_text(fs::path(CLMARCH_DOCGEN_DIR) / "clmarch.1"));

  const fs::path image = prefix / "torus.png";
  const auto render = run_shell(shell_quote((prefix / "bin/clmarch").string()) + " render " +
                                shell_quote((prefix / "share/clmarch/scenes/torus.yaml").string()) +
                                " --backend reference --size 48x27 -o " + shell_quote(image.string()));
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const testing::Image rendered = testing::read_image(image);
  EXPECT_EQ(rendered.width, 48);
  EXPECT_EQ(rendered.height, 27);
  const auto version = run_shell(shell_quote((prefix / "bin/clmarch").string()) + " --version");
  EXPECT_EQ(version.out, std::string("clmarch ") + CLMARCH_VERSION + "\n");
}

}  // namespace
}  // namespace clmarch
