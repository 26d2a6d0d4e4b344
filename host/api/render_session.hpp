// A render session: renders scenes on one backend after another and keeps the OpenCL renderer and
// its program between them, so that frames, sweeps and edits of numbers build a program at most
// twice per shape of the scene (the CLI's --frames, the Python module's Session, the preview).
#pragma once

#include "codegen/kernel_source.hpp"
#include "codegen/varying_literals.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace clmarch {

enum class Backend { OpenCl, Reference };
/// The names --backend and the Python module take, indexed by Backend.
inline constexpr const char* kBackendNames[] = {"opencl", "reference"};

/// The backend called name; throws InputError "what: backend must be opencl or reference (got 'x')".
Backend parse_backend(const std::string& name, const std::string& what);

/// What one frame asks of the renderer besides the scene.
struct FrameRequest {
  Backend backend = Backend::OpenCl;
  /// Every buffer (normals, ids, the shading's layers) besides what the scene's view needs: the
  /// program of `render --buffers`.
  bool buffers = true;
  /// The status plane also where the purpose does not need it (`render --stats`).
  bool ray_status = false;
  /// Called with the exact OpenCL C source of the frame's program, before it is built or when it
  /// is reused (--dump-kernel); empty: not called.
  std::function<void(const std::string& source)> on_source;
};

/// The kernel work a frame needs: buffers include normals; the image, what its view shows.
KernelPurpose purpose_for(const Scene& scene, bool want_buffers);

/// The device and packet width of a session's OpenCL renders (the defaults: first GPU, else first
/// CPU; the device's lanes).
struct SessionOptions {
  std::optional<int> device;
  std::optional<int> lanes;
};

class RenderSession {
 public:
  explicit RenderSession(SessionOptions options = {});

  /// Tells the session a frame of an animation to come (the CLI loads a sample of them first):
  /// the literals that differ among such frames are read from the values buffer, the others
  /// spelled, so that the frames share one program per shape.
  void expect_frame(const Scene& frame);
  /// Makes the frame's OpenCL program current without rendering (a --dump-kernel run).
  void prepare(const Scene& scene, const FrameRequest& request);
  /// Renders scene: the CPU reference's full frame, or on OpenCL with the current program when it
  /// renders scene, else with another, built or found. The status plane is filled on both backends
  /// where ray_status asks; the view is not drawn (apply_view).
  RenderResult render(const Scene& scene, const FrameRequest& request);

  /// The OpenCL C of the current program (empty before the first OpenCL frame).
  const std::string& source() const;
  /// Programs compiled for this session's frames (a program found among those the process keeps
  /// is not counted).
  std::uint64_t programs_built() const { return programs_built_; }

 private:
  OpenClOptions frame_options(const Scene& scene, const FrameRequest& request);
  OpenClRenderer& renderer_for(const Scene& scene, const FrameRequest& request);

  SessionOptions options_;
  /// The renderers of the last kKeptRenderers image sizes or purposes, the current one first (a
  /// preview alternates a coarse frame and the full one; each keeps its buffers).
  static constexpr std::size_t kKeptRenderers = 2;
  std::list<std::unique_ptr<OpenClRenderer>> renderers_;
  bool expecting_frames_ = false;
  VaryingLiterals varying_;
  /// The first literals seen of each shape (code_shape of the march code), and whether a later
  /// scene of that shape had others: then every literal goes to the values buffer.
  struct ShapeValues {
    std::vector<float> first;
    bool edited = false;
  };
  std::map<std::string, ShapeValues> shapes_;
  std::uint64_t programs_built_ = 0;
};

/// The CPU reference's frame of scene, with the figures --stats prints for it.
RenderResult render_reference_frame(const Scene& scene);

}  // namespace clmarch
