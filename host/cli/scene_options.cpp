// Shared scene options.
#include "cli/scene_options.hpp"

#include "api/scene_request.hpp"
#include "common/errors.hpp"
#include "scene/scene_loader.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <regex>

namespace clmarch {

void add_scene_options(CLI::App& command, SceneOptions& options) {
  // FILE and DIR value names also tell the completions (cli/docgen/) to offer files or folders.
  command.add_option("scene", options.scene_path, "Scene file (YAML or JSON), e.g. scenes/torus.yaml")
      ->required()
      ->type_name("FILE");
  command.add_option("--size", options.size, "Image size WxH, overriding render.width/height (e.g. --size 320x180)");
  command
      .add_option("--set", options.sets,
                  "Override any scene key: key.path=value, e.g. --set render.epsilon=1e-5 "
                  "--set camera.position=[0,0,1e6] (list items by index: sdf.union.0.sphere.radius=2)")
      ->take_all();
  command.add_option(
      "--device", options.device,
      "OpenCL device index from `clmarch devices` (default: first GPU, else first CPU; e.g. --device 0)");
  command
      .add_option("--lanes", options.lanes,
                  "Pixels each work-item marches as one vector (default: 16 on CPUs, 1 on GPUs; e.g. --lanes 1)")
      ->check(CLI::Validator(
          [](std::string& value) {
            return value == "1" || value == "4" || value == "8" || value == "16"
                       ? std::string()
                       : "must be 1, 4, 8 or 16 (got '" + value + "')";
          },
          "1|4|8|16", "LANES"));
  command
      .add_option("--time", options.time,
                  "Time t in seconds for expressions in the scene, e.g. center: [cos(t), sin(t), 0]")
      ->check(finite_number([](double) { return true; }, "a finite number of seconds"));
  command
      .add_option("--samples", options.samples,
                  "Rays per pixel, anti-aliasing the image (render.samples, 1..1024; e.g. --samples 16)")
      ->check(CLI::Validator(
          [](std::string& value) {
            const bool digits =
                !value.empty() && value.size() <= 4 && value.find_first_not_of("0123456789") == std::string::npos;
            const int n = digits ? std::stoi(value) : 0;
            return n >= 1 && n <= kMaxSamples ? std::string() : "must be an integer in [1, 1024] (got '" + value + "')";
          },
          "1..1024", "N"));
}

CLI::Validator finite_number(const std::function<bool(double)>& accept, const std::string& expected) {
  return CLI::Validator(
      [accept, expected](std::string& text) {
        double value = 0.0;
        // from_chars takes no '+' sign; a shell user may write one.
        const char* begin = text.data();
        if (text.size() > 1 && text[0] == '+' && text[1] != '-') ++begin;
        const auto [end, error] = std::from_chars(begin, text.data() + text.size(), value);
        const bool ok =
            error == std::errc() && end == text.data() + text.size() && std::isfinite(value) && accept(value);
        return ok ? std::string() : "must be " + expected + " (got '" + text + "')";
      },
      "", "NUMBER");
}

std::pair<int, int> parse_size(const std::string& text) {
  static const std::regex pattern(R"(^(\d{1,6})x(\d{1,6})$)");
  static const std::regex long_digits(R"(^\d+x\d+$)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) {
    if (std::regex_match(text, long_digits)) {
      throw InputError(fmt::format("--size {}: width and height must be in [1, 65536]", text));
    }
    throw InputError(fmt::format("--size {}: expected WIDTHxHEIGHT, e.g. 640x360", text));
  }
  const int width = std::stoi(match[1].str());
  const int height = std::stoi(match[2].str());
  if (width < 1 || height < 1 || width > 65536 || height > 65536) {
    throw InputError(
        fmt::format("--size {}: width and height must be in [1, 65536] (got {} x {})", text, width, height));
  }
  if (!image_size_fits(width, height)) {
    throw InputError(fmt::format("--size {}: too many pixels (got {}, expected at most {})", text,
                                 static_cast<long long>(width) * height, kMaxPixels));
  }
  return {width, height};
}

Scene load_scene_with_options(const SceneOptions& options, std::optional<double> time) {
  SceneRequest request;
  request.path = options.scene_path;
  for (const std::string& set : options.sets) request.overrides.push_back(parse_override(set));
  if (!options.size.empty()) {
    request.size = parse_size(options.size);
    request.size_label = "--size " + options.size;
  }
  request.time = time ? *time : options.time.value_or(0.0);
  request.samples = options.samples;
  return load_scene(request);
}

OpenClOptions opencl_options(const SceneOptions& options) {
  OpenClOptions out;
  out.device = options.device;
  out.lanes = options.lanes;
  return out;
}

SessionOptions session_options(const SceneOptions& options) { return {options.device, options.lanes}; }

}  // namespace clmarch
