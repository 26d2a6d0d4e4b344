// Keeping programs across a session's frames.
#include "api/render_session.hpp"

#include "cl/device_program.hpp"
#include "codegen/sdf_codegen.hpp"
#include "common/errors.hpp"
#include "common/log.hpp"
#include "reference/reference_cones.hpp"
#include "reference/reference_renderer.hpp"

#include <fmt/format.h>
#include <tbb/task_arena.h>

#include <bit>
#include <chrono>
#include <cstring>

namespace clmarch {

Backend parse_backend(const std::string& name, const std::string& what) {
  for (int b = 0; b < static_cast<int>(std::size(kBackendNames)); ++b) {
    if (name == kBackendNames[b]) return static_cast<Backend>(b);
  }
  throw InputError(fmt::format("{}: backend must be opencl or reference (got '{}')", what, name));
}

KernelPurpose purpose_for(const Scene& scene, bool want_buffers) {
  switch (scene.shading.view) {
    case View::Shaded:
      return want_buffers ? KernelPurpose::Buffers : KernelPurpose::Color;
    // The samples a pixel gets follow its color's edges: the shaded program decides them.
    case View::Samples:
      return want_buffers ? KernelPurpose::Buffers : KernelPurpose::Color;
    case View::Normals:
      return KernelPurpose::Normals;
    // The status view's program writes the status plane (Normals does).
    case View::Status:
      return KernelPurpose::Normals;
    case View::Depth:
    case View::Steps:
      return want_buffers ? KernelPurpose::Normals : KernelPurpose::DepthSteps;
  }
  return KernelPurpose::Shaded;
}

RenderResult render_reference_frame(const Scene& scene) {
  log_verbose(fmt::format("rendering on the CPU reference (double precision, {} threads)",
                          tbb::this_task_arena::max_concurrency()));
  RenderResult result;
  const auto start = std::chrono::steady_clock::now();
  const std::optional<ConeStarts> cones = reference_cones_if_used(scene);
  result.buffers = render_reference(scene, cones);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  result.stats.device = "CPU reference (double)";
  result.stats.precision = Precision::Double;
  result.stats.kernel_ms = ms;
  for (float s : result.buffers.plane(Channel::Steps)) result.stats.steps += static_cast<std::uint64_t>(s);
  for (float s : result.buffers.plane(Channel::WallSteps)) result.stats.wall_steps += static_cast<std::uint64_t>(s);
  result.stats.out_of_steps = result.buffers.rays_with_status(RayStatus::OutOfSteps);
  result.stats.out_of_distance = result.buffers.rays_with_status(RayStatus::OutOfDistance);
  if (cones) {
    for (int s : cones->steps) result.stats.coarse_steps += static_cast<std::uint64_t>(s);
  }
  result.stats.rays_per_s = static_cast<double>(scene.render.width) * scene.render.height / (ms * 1e-3);
  return result;
}

RenderSession::RenderSession(SessionOptions options) : options_(options) {}

void RenderSession::expect_frame(const Scene& frame) {
  expecting_frames_ = true;
  varying_.add(frame);
}

OpenClOptions RenderSession::frame_options(const Scene& scene, const FrameRequest& request) {
  OpenClOptions cl;
  cl.device = options_.device;
  cl.lanes = options_.lanes;
  cl.ray_status = request.ray_status;
  cl.purpose = purpose_for(scene, request.buffers);
  if (expecting_frames_) {
    // A frame between the samples may vary more: its shape's program is built again, once.
    cl.value_slots = varying_.add(scene);
    return cl;
  }
  // Edits of numbers without foreknowledge (a sweep, an editor): the first scene of a shape spells
  // its literals, which is fastest warm; once another scene of that shape has other numbers, its
  // program reads them all from the values buffer, so that no later edit of a number builds.
  SdfCode code = march_scene_code(scene);
  const auto [it, is_new] = shapes_.try_emplace(code_shape(code.source));
  ShapeValues& shape = it->second;
  if (is_new) {
    shape.first = std::move(code.literals);
  } else if (!shape.edited) {
    shape.edited = shape.first.size() != code.literals.size() ||
                   std::memcmp(shape.first.data(), code.literals.data(), shape.first.size() * sizeof(float)) != 0;
  }
  cl.literals_in_buffer = shape.edited;
  return cl;
}

OpenClRenderer& RenderSession::renderer_for(const Scene& scene, const FrameRequest& request) {
  OpenClOptions cl = frame_options(scene, request);
  for (auto kept = renderers_.begin(); kept != renderers_.end(); ++kept) {
    if (!(*kept)->can_render(scene, cl)) continue;
    log_verbose("same program as an earlier frame: no build");
    renderers_.splice(renderers_.begin(), renderers_, kept);
    OpenClRenderer& renderer = *renderers_.front();
    if (request.on_source) request.on_source(renderer.source());
    renderer.set_scene(scene);
    return renderer;
  }
  if (request.on_source) cl.before_build = request.on_source;
  const std::uint64_t compiled_before = device_programs_compiled();
  // The least recent renderer goes first: its buffers may be large.
  if (renderers_.size() >= kKeptRenderers) renderers_.pop_back();
  renderers_.push_front(std::make_unique<OpenClRenderer>(scene, cl));
  programs_built_ += device_programs_compiled() - compiled_before;
  return *renderers_.front();
}

void RenderSession::prepare(const Scene& scene, const FrameRequest& request) {
  if (request.backend == Backend::OpenCl) renderer_for(scene, request);
}

RenderResult RenderSession::render(const Scene& scene, const FrameRequest& request) {
  if (request.backend == Backend::Reference) return render_reference_frame(scene);
  return renderer_for(scene, request).render();
}

const std::string& RenderSession::source() const {
  static const std::string none;
  return renderers_.empty() ? none : renderers_.front()->source();
}

}  // namespace clmarch
