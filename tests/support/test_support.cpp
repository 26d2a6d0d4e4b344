// Test helpers.
#include "support/test_support.hpp"

#include "cl/devices.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "frame/frame_buffers.hpp"
#include "scene/scene_loader.hpp"

#include <OpenImageIO/imageio.h>
#include <stdexcept>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include <sys/wait.h>

namespace clmarch::testing {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string compiler_warnings(const std::string& build_log) {
  std::string warnings;
  std::istringstream lines(build_log);
  for (std::string line; std::getline(lines, line);) {
    std::string lower = line;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    if (lower.find("warning") == std::string::npos) continue;
    if (lower.find("is a kernel, so overriding noinline attribute") != std::string::npos) continue;
    warnings += line + "\n";
  }
  return warnings;
}

std::string front_end_warnings(const std::string& source) {
  const DeviceEntry device = select_device(std::nullopt);
  const cl::Context context(device.device);
  cl::Program program(context, source);
  try {
    program.compile(kLoggedBuildOptions.c_str());
  } catch (const cl::Error&) {
    return "the source does not compile:\n" + program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device.device);
  }
  return compiler_warnings(program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device.device));
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out.append("'\\''");
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

Scene scene_from_yaml(const std::string& yaml, double time) { return load_scene_text(yaml, "test.yaml", {}, time); }

std::string error_of(const std::string& yaml, const std::vector<SceneOverride>& overrides) {
  try {
    load_scene_text(yaml, "s.yaml", overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::filesystem::path source_path(const std::string& relative) {
  return std::filesystem::path(CLMARCH_SOURCE_DIR) / relative;
}

std::vector<std::string> shipped_scene_names() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(source_path("scenes"))) {
    if (entry.path().extension() == ".yaml" || entry.path().extension() == ".json")
      names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

CommandResult run_clmarch(const std::vector<std::string>& args, const std::vector<std::string>& environment) {
  return run_clmarch_in_shell("", args, environment);
}

CommandResult run_clmarch_in_shell(const std::string& shell_prefix, const std::vector<std::string>& args,
                                   const std::vector<std::string>& environment) {
  std::string command = shell_prefix;
  if (!environment.empty()) {
    command.append("env");
    for (const std::string& setting : environment) command.append(" ").append(shell_quote(setting));
    command.append(" ");
  } else if (!shell_prefix.empty()) {
    command.append("exec ");
  }
  command.append(shell_quote(CLMARCH_BINARY));
  for (const std::string& a : args) command.append(" ").append(shell_quote(a));
  return run_shell(command);
}

CommandResult run_shell(const std::string& command) {
  TempDir capture;
  const std::string redirected = "{ " + command + "\n} >" + shell_quote((capture / "out").string()) + " 2>" +
                                 shell_quote((capture / "err").string()) + " </dev/null";
  CommandResult result;
  const int status = std::system(redirected.c_str());
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = read_text(capture / "out");
  result.err = read_text(capture / "err");
  return result;
}

Image read_image(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw std::runtime_error("cannot read " + path.string() + ": " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
    throw std::runtime_error("cannot read " + path.string() + ": " + in->geterror());
  }
  return image;
}

TempDir::TempDir() {
  std::random_device seed;
  path_ = std::filesystem::temp_directory_path() / ("clmarch-test-" + std::to_string(seed()));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::vector<std::string> TempDir::files() const {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(path_))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

Node leaf(NodeParams params, NodeKind kind) {
  Node n;
  n.kind = kind;
  n.params = std::move(params);
  return n;
}

double total_steps(const FrameBuffers& buffers) {
  double sum = 0.0;
  for (float s : buffers.plane(Channel::Steps)) sum += s;
  return sum;
}

PlaneComparison compare_planes(const FrameBuffers& got, const FrameBuffers& want) {
  PlaneComparison result;
  if (got.width != want.width || got.height != want.height) {
    result.differing = "image sizes";
    return result;
  }
  for (int c = 0; c < kChannelCount; ++c) {
    const std::vector<float>& a = got.planes[static_cast<std::size_t>(c)];
    const std::vector<float>& b = want.planes[static_cast<std::size_t>(c)];
    if (a.size() != b.size() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) != 0) {
      result.differing += std::string(result.differing.empty() ? "" : " ") + kChannelNames[c];
    } else if (!a.empty()) {
      ++result.compared;
    }
  }
  return result;
}

CancellationReset::~CancellationReset() { cancellation_requested().store(false); }

}  // namespace clmarch::testing
