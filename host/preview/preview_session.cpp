// The preview's scene, session and frames.
#include "preview/preview_session.hpp"

#include "api/scene_request.hpp"
#include "api/stats_json.hpp"
#include "common/errors.hpp"
#include "image/image_writer.hpp"
#include "scene/camera_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace clmarch {
namespace {

nlohmann::json vec3_json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void check_preview_camera(const PreviewCamera& camera) {
  if (!finite(camera.position) || !finite(camera.look_at) || !finite(camera.up) || !std::isfinite(camera.fov_degrees))
    throw InputError("camera: every number must be finite");
  if (!(camera.fov_degrees > 0.0 && camera.fov_degrees < 180.0))
    throw InputError(fmt::format("camera: fov must be in (0, 180) degrees (got {})", camera.fov_degrees));
  const glm::dvec3 forward = camera.look_at - camera.position;
  if (!(glm::length(forward) > 0.0)) throw InputError("camera: position and look_at must differ");
  if (!(glm::length(glm::cross(glm::normalize(forward), camera.up)) > 1e-9))
    throw InputError("camera: up must not be along the view direction (or zero)");
}

PreviewSession::PreviewSession(PreviewOptions options) : options_(std::move(options)), session_(options_.session) {
  scene_ = load(0.0);
  watched_ = look_at_files();
}

Scene PreviewSession::load(double time) const {
  SceneRequest request;
  request.path = options_.scene_path;
  request.time = time;
  request.size = options_.size;
  request.size_label = "--size";
  return load_scene(request);
}

std::map<std::string, PreviewSession::WatchedFile> PreviewSession::look_at_files() const {
  std::map<std::string, WatchedFile> files;
  std::vector<std::string> paths = scene_.instance_files;
  paths.push_back(options_.scene_path);
  for (const std::string& path : paths) {
    WatchedFile& file = files[path];
    std::error_code error;
    file.time = std::filesystem::last_write_time(path, error);
    file.exists = !error;
    file.size = file.exists ? std::filesystem::file_size(path, error) : 0;
  }
  return files;
}

bool PreviewSession::refresh() {
  const std::lock_guard lock(state_mutex_);
  std::map<std::string, WatchedFile> now = look_at_files();
  const bool changed = std::any_of(now.begin(), now.end(), [&](const auto& entry) {
    const auto before = watched_.find(entry.first);
    return before == watched_.end() || before->second.exists != entry.second.exists ||
           before->second.time != entry.second.time || before->second.size != entry.second.size;
  });
  if (!changed) return false;
  watched_ = std::move(now);
  ++version_;
  try {
    scene_ = load(scene_.time);
    error_.clear();
    // The instance files the new scene reads are watched from now on.
    watched_ = look_at_files();
  } catch (const InputError& e) {
    error_ = e.what();
  }
  return true;
}

nlohmann::json PreviewSession::state() {
  refresh();
  const std::lock_guard lock(state_mutex_);
  const Camera& c = scene_.camera;
  return {{"version", version_},
          {"error", error_},
          {"scene", options_.scene_path},
          {"camera",
           {{"position", vec3_json(c.position)},
            {"look_at", vec3_json(c.look_at)},
            {"up", vec3_json(c.up)},
            {"fov", c.fov_degrees}}},
          {"width", scene_.render.width},
          {"height", scene_.render.height},
          {"animated", scene_.animated},
          {"time", scene_.time},
          {"sequence", latest_sequence_.load()},
          {"stats", last_stats_}};
}

std::optional<PreviewFrame> PreviewSession::frame(const FrameQuery& query) {
  std::uint64_t seen = latest_sequence_.load();
  while (query.sequence > seen && !latest_sequence_.compare_exchange_weak(seen, query.sequence)) {
  }
  if (query.camera) check_preview_camera(*query.camera);
  if (query.time && !std::isfinite(*query.time)) throw InputError("t: the time must be a finite number of seconds");
  const std::lock_guard render_lock(render_mutex_);
  if (query.sequence < latest_sequence_.load()) return std::nullopt;
  Scene scene;
  {
    const std::lock_guard lock(state_mutex_);
    if (query.time && *query.time != scene_.time) {
      try {
        scene_ = load(*query.time);
      } catch (const InputError& e) {
        error_ = e.what();
      }
    }
    scene = scene_;
  }
  if (query.camera) {
    scene.camera.position = query.camera->position;
    scene.camera.look_at = query.camera->look_at;
    scene.camera.up = query.camera->up;
    scene.camera.fov_degrees = query.camera->fov_degrees;
  }
  if (query.coarse) {
    scene.render.width = std::max(1, scene.render.width / 4);
    scene.render.height = std::max(1, scene.render.height / 4);
    scene.render.samples = 1;
  }
  FrameRequest request;
  request.buffers = true;
  request.ray_status = true;
  RenderResult result = session_.render(scene, request);
  if (!query.coarse) last_full_ = FullFrame{result.buffers, scene.camera};
  draw_preview_view(result.buffers, query.view, scene.render);
  PreviewFrame frame;
  frame.png = encode_color_image(result.buffers, "png");
  frame.stats = render_stats_json(Backend::OpenCl, scene, result.stats);
  const double pixels = static_cast<double>(scene.render.width) * scene.render.height;
  frame.stats["steps_per_pixel"] = static_cast<double>(result.stats.steps) / pixels;
  frame.stats["programs_built"] = session_.programs_built();
  frame.stats["coarse"] = query.coarse;
  frame.stats["view"] = kPreviewViewNames[static_cast<int>(query.view)];
  {
    const std::lock_guard lock(state_mutex_);
    last_stats_ = frame.stats;
  }
  return frame;
}

std::optional<nlohmann::json> PreviewSession::pixel(int x, int y) {
  const std::lock_guard render_lock(render_mutex_);
  if (!last_full_) return std::nullopt;
  const FrameBuffers& b = last_full_->buffers;
  if (x < 0 || y < 0 || x >= b.width || y >= b.height) return std::nullopt;
  const float depth = b.at(Channel::Depth, x, y);
  const auto status = static_cast<int>(b.at(Channel::Status, x, y));
  nlohmann::json out = {{"x", x},
                        {"y", y},
                        {"steps", b.at(Channel::Steps, x, y)},
                        {"id", b.at(Channel::Id, x, y)},
                        {"status", status >= 0 && status < 4 ? kRayStatusNames[status] : "unknown"}};
  if (std::isfinite(depth)) {
    const CameraBasis basis = camera_basis(last_full_->camera, b.width, b.height);
    out["depth"] = depth;
    out["position"] = vec3_json(basis.origin + static_cast<double>(depth) * pixel_ray_direction(basis, x, y));
    out["normal"] = {b.at(Channel::NX, x, y), b.at(Channel::NY, x, y), b.at(Channel::NZ, x, y)};
  } else {
    out["depth"] = nullptr;
  }
  return out;
}

}  // namespace clmarch
