// Loading a requested scene.
#include "api/scene_request.hpp"

#include "common/errors.hpp"
#include "render/host_memory.hpp"

#include <fmt/format.h>

namespace clmarch {

void check_host_memory(const Scene& scene, const std::string& size_label) {
  const std::optional<AvailableMemory> available = available_host_memory();
  if (!available) return;
  const std::string shortfall =
      host_memory_shortfall(scene.render.width, scene.render.height, *available, scene.render.samples);
  if (shortfall.empty()) return;
  if (!size_label.empty()) throw InputError(fmt::format("{}: {}", size_label, shortfall));
  const std::string where = scene.size_origin.empty() ? scene.source_name : scene.size_origin;
  throw InputError(fmt::format("{}: render.width x render.height: {}", where, shortfall));
}

Scene load_scene(const SceneRequest& request) {
  Scene scene = request.path.empty()
                    ? load_scene_text(request.text, request.source_name, request.overrides, request.time)
                    : load_scene_file(request.path, request.overrides, request.time);
  if (request.size) {
    const auto [width, height] = *request.size;
    const bool sides = width >= 1 && height >= 1 && width <= kMaxImageSide && height <= kMaxImageSide;
    if (!sides || !image_size_fits(width, height)) {
      throw InputError(fmt::format("{}: size {} x {}: width and height must be in [1, {}] and their product at most {}",
                                   request.size_label.empty() ? scene.source_name : request.size_label, width, height,
                                   kMaxImageSide, kMaxPixels));
    }
    scene.render.width = request.size->first;
    scene.render.height = request.size->second;
  }
  if (request.samples) {
    if (*request.samples < 1 || *request.samples > kMaxSamples) {
      throw InputError(
          fmt::format("{}: samples must be in [1, {}] (got {})", scene.source_name, kMaxSamples, *request.samples));
    }
    scene.render.samples = *request.samples;
  }
  check_host_memory(scene, request.size ? request.size_label : "");
  return scene;
}

}  // namespace clmarch
