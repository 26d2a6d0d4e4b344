// Helpers shared by the tests: scenes from inline YAML, running the clmarch executable, temp folders.
#pragma once

#include "cl/device_program.hpp"
#include "scene/scene.hpp"
#include "scene/scene_loader.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace clmarch {
struct FrameBuffers;
}

namespace clmarch::testing {

/// A scene from YAML text (messages name it "test.yaml").
Scene scene_from_yaml(const std::string& yaml, double time = 0.0);

/// The loader's message for YAML text named "s.yaml" with overrides, or "no error".
std::string error_of(const std::string& yaml, const std::vector<SceneOverride>& overrides = {});

/// A path inside the source tree (scenes/torus.yaml).
std::filesystem::path source_path(const std::string& relative);

/// The file names of the scenes shipped in scenes/ (.yaml and .json), sorted: enumerated, so that a
/// new scene is covered by every test that loops over them the day it is added.
std::vector<std::string> shipped_scene_names();

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// Runs the built clmarch executable with args (no shell quoting needed for plain arguments);
/// environment holds extra NAME=VALUE settings for it.
CommandResult run_clmarch(const std::vector<std::string>& args, const std::vector<std::string>& environment = {});

/// Like run_clmarch, after shell_prefix (commands ending in "; ", e.g. "ulimit -f 8; ").
CommandResult run_clmarch_in_shell(const std::string& shell_prefix, const std::vector<std::string>& args,
                                   const std::vector<std::string>& environment = {});

/// Runs a /bin/sh command line with stdin from /dev/null; its stdout, stderr and exit code.
CommandResult run_shell(const std::string& command);

/// The whole file as text (empty if it cannot be read).
std::string read_text(const std::filesystem::path& path);

/// The lines of an OpenCL build log that speak of warnings, in any case ("" if none), except
/// NVIDIA's "Function F is a kernel, so overriding noinline attribute" that its drivers since 550
/// print for every kernel of every source.
std::string compiler_warnings(const std::string& build_log);

/// Build options (kBuildOptions and a define of their own) for a build whose log is checked for
/// warnings: PoCL's kernel cache keeps a program's binary but not its build log, so a build of the
/// same source and options by another process (another test's render) would serve this one with
/// an empty log.
inline const std::string kLoggedBuildOptions = std::string(kBuildOptions) + " -DCLMARCH_LOGGED_BUILD";

/// The warnings (compiler_warnings) of compiling source for the default device with clang's front
/// end alone (clCompileProgram, kLoggedBuildOptions): where warnings come from, in about half the
/// time of a whole build (no linking of the driver's built-in library). A source that does not
/// compile gives its whole log.
std::string front_end_warnings(const std::string& source);

/// s in single quotes for /bin/sh.
std::string shell_quote(const std::string& s);

/// An image read with OpenImageIO: interleaved channels as float in [0, 1] for 8-bit files.
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;
  float at(int i, int j, int c) const { return pixels[(static_cast<std::size_t>(j) * width + i) * channels + c]; }
};
Image read_image(const std::filesystem::path& path);

/// A fresh empty folder under the system temp folder, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  /// Names of the files in the folder, sorted.
  std::vector<std::string> files() const;

 private:
  std::filesystem::path path_;
};

/// A node of the kind with its parameters and no children.
Node leaf(NodeParams params, NodeKind kind);

/// The sum of the Steps plane of a render: the march's work over the whole image.
double total_steps(const FrameBuffers& buffers);

/// Two renders' channels compared as bits (NaN-safe, -0 apart from +0): how many both filled, and
/// the names of those that differ (empty: none), or why they cannot be compared.
struct PlaneComparison {
  int compared = 0;
  std::string differing;
};
PlaneComparison compare_planes(const FrameBuffers& got, const FrameBuffers& want);

/// Resets the process-wide cancellation flag (common/cancellation.hpp) however the test ends.
struct CancellationReset {
  CancellationReset() = default;
  ~CancellationReset();
  CancellationReset(const CancellationReset&) = delete;
  CancellationReset& operator=(const CancellationReset&) = delete;
};

}  // namespace clmarch::testing
