// Renders a scene on an OpenCL device: generate the program, build it, march, read the buffers back.
#pragma once

#include "codegen/kernel_source.hpp"
#include "frame/frame_buffers.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace clmarch {

struct OpenClOptions {
  /// Device index of `clmarch devices`; default: first GPU, else first CPU.
  std::optional<int> device;
  /// Pixels per work-item; default from the device (default_lanes).
  std::optional<int> lanes;
  KernelPurpose purpose = KernelPurpose::Shaded;
  /// Precision, native math and fast math of the program (default: float, precise builtins).
  KernelVariant variant;
  /// Literals of the scene's distance function and shading that the march program reads from its
  /// values buffer instead of spelling them (march_scene_code): the values an animation changes,
  /// so that its frames share one program (VaryingLiterals). Empty: every literal is spelled.
  ValueSlots value_slots;
  /// Every literal read from the values buffer where the scene's render.literals is auto (a session
  /// whose scenes edit numbers: one program per shape); inline and buffer decide for themselves.
  bool literals_in_buffer = false;
  /// Called with the exact program source before it is built (--dump-kernel writes it to a file,
  /// so that a program that fails to build can be read); empty: not called.
  std::function<void(const std::string& source)> before_build;
  /// Most pixels per dispatch; 0: as many as the device's largest buffer allows (capped so that
  /// progress and Ctrl-C stay responsive).
  std::size_t max_chunk_pixels = 0;
  /// The status plane also where the purpose does not need it (KernelOptions::ray_status).
  bool ray_status = false;
};

/// Figures of one OpenCL render (--stats).
struct RenderStats {
  std::string device;
  int lanes = 1;
  /// The program's arithmetic (render.precision, or a sweep's precision).
  Precision precision = Precision::Float;
  double build_ms = 0.0;
  /// From the profiling events of the march kernel (and of the coarse cone pass).
  double kernel_ms = 0.0;
  /// Sum of the steps buffer: march iterations over all pixels.
  std::uint64_t steps = 0;
  /// The part of steps that stepped to a cell wall (tiling's cell traversal).
  std::uint64_t wall_steps = 0;
  /// Steps of the coarse cone pass, one cone per block of pixels (not part of steps).
  std::uint64_t coarse_steps = 0;
  /// Centre rays that ran out of render.max_steps, and that reached render.max_distance (the
  /// status channel; 0 where the program wrote none: OpenClOptions::ray_status).
  std::uint64_t out_of_steps = 0;
  std::uint64_t out_of_distance = 0;
  double rays_per_s = 0.0;
  /// Dispatches the image was split into.
  int chunks = 1;
  /// Where the program keeps the scene's numbers (render.literals as taken): "inline" or "buffer".
  std::string literals = "inline";
  /// Whether the program calls its stages or inlines them (render.stages as taken): "called" or
  /// "inline".
  std::string stages = "inline";
};

struct RenderResult {
  FrameBuffers buffers;
  RenderStats stats;
};

/// Renders scene at scene.render.width x height, in chunks of pixels when the image's buffers exceed
/// what the device allocates at once. Without shading in the purpose, R, G, B stay 0; without
/// normals, N stays 0. Polls cancellation between chunks.
RenderResult render_opencl(const Scene& scene, const OpenClOptions& options);

/// Rows a band of render_rows starts at a multiple of: the coarse pass's block, which every packet
/// height (1, 2 or 4 rows) divides.
inline constexpr int kBandRowAlignment = 8;

/// render_opencl again and again (benchmarks, the frames of an animation): the program, the kernel
/// and the output buffer are made once, so later renders neither build nor touch fresh buffer
/// pages, and time the march alone.
class OpenClRenderer {
 public:
  OpenClRenderer(const Scene& scene, const OpenClOptions& options);
  ~OpenClRenderer();
  OpenClRenderer(const OpenClRenderer&) = delete;
  OpenClRenderer& operator=(const OpenClRenderer&) = delete;

  /// Renders the current scene. Its build_ms is the build's on the first render, 0 after.
  RenderResult render();
  /// Renders rows first_row .. first_row + rows - 1 of the current scene's image into buffers of
  /// width x rows (a tile of a distributed render): bit for bit the pixels of render()'s whole
  /// image, since the camera, the coarse pass and the packets are the whole image's. first_row must
  /// be a multiple of kBandRowAlignment. The coarse pass runs once per scene, at its first band.
  RenderResult render_rows(int first_row, int rows);

  /// Whether scene can be rendered with this program and buffers: the same image size, options
  /// (but before_build) and program key (program_key), so only what the kernel takes as arguments
  /// differs (the camera, march limits and shading numbers, the lights, the literals at value_slots).
  bool can_render(const Scene& scene, const OpenClOptions& options) const;
  /// Makes scene the current one; can_render(scene, ...) must hold.
  void set_scene(const Scene& scene);
  /// The generated source of the program.
  const std::string& source() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// The scene's generated map() and map_color() evaluated at points on the device.
struct PointSamples {
  /// In the program's precision: floats, or a double program's doubles.
  std::vector<double> distance;
  /// Distance as map_color() computes it (must equal distance).
  std::vector<double> color_distance;
  std::vector<glm::vec3> albedo;
  /// The number of the primitive whose material map_color() gives (the id channel's).
  std::vector<float> primitive;
};
/// points are offsets from origin, which the program adds in its precision (a double program keeps
/// the offsets' precision at a far origin); they travel in the program's precision too.
PointSamples eval_points_opencl(const Scene& scene, const std::vector<glm::dvec3>& points, const OpenClOptions& options,
                                const glm::dvec3& origin = glm::dvec3(0.0));

}  // namespace clmarch
