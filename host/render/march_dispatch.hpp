// How the march kernel is dispatched: programs, packet tiles, chunks of rows and the per-frame
// parameters. Shared by the renderer and the benchmark's recording march, so both run the kernel
// exactly alike.
#pragma once

#include "cl/device_program.hpp"
#include "device_types.h"
#include "render/opencl_renderer.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace clmarch {

/// A program built for one purpose, with its packet width, packets per work-item and the output
/// planes its march kernel writes.
struct PreparedProgram {
  DeviceProgram program;
  int lanes = 1;
  int packets_per_item = 1;
  std::vector<int> planes;
  /// The generated OpenCL C it was built from, and what it was generated with.
  std::string source;
  KernelOptions kernel_options;
};

/// Generates and builds the scene's program for purpose (writing it to options.dump_kernel_path
/// first when set).
PreparedProgram prepare_program(const Scene& scene, const OpenClOptions& options, KernelPurpose purpose);

/// Columns of the tile a packet of `lanes` pixels covers (PACKET_WIDTH of kernels/lanes.cl).
int packet_width(int lanes);
/// Rows of that tile (PACKET_HEIGHT).
inline int packet_height(int lanes) { return lanes / packet_width(lanes); }

/// For the march kernel a dispatch covers chunk_rows image rows, packets_per_item packets per
/// work-item, and its output planes hold those rows, width floats each; for point kernels, LANES
/// consecutive points per work-item.
struct Dispatch {
  std::size_t global_items = 0;
  std::size_t local_items = 0;
  /// Pixels of a packet's tile (march kernel).
  int tile_width = 1;
  int tile_height = 1;
  int chunk_rows = 0;
  /// Floats per plane.
  std::size_t plane_stride = 0;
};

/// The march kernel's dispatch of a width x height image in chunks of at most max_pixels (rounded
/// to whole rows of tiles, at least one) for program.
Dispatch plan_tile_dispatch(const PreparedProgram& program, int width, int height, std::size_t max_pixels);
/// A point kernel's dispatch of count points.
Dispatch plan_point_dispatch(const DeviceEntry& device, std::size_t count, int lanes);
/// Pixels per dispatch that the device's allocation limits allow (capped so that progress and
/// Ctrl-C stay responsive).
std::size_t chunk_pixels_for(const DeviceEntry& device);

/// Tiles of an image, by their column and row in the grid of tile_width x tile_height tiles, both
/// ends included; empty when a first is past its last.
struct TileRange {
  int first_column = 0, last_column = -1;
  int first_row = 0, last_row = -1;
};
/// The tiles whose centre ray (the unnormalised q = f + sx r + sy u through the tile's centre) may
/// pass within reach of the point c (relative to the camera): every tile for which the march
/// kernel's scalar test |c x q|^2 <= reach^2 |q|^2 holds, in float, lies inside. Outside it the
/// kernel skips tiles by integer comparisons instead. Solved per row of tiles in double, with
/// margins for the kernel's float arithmetic.
TileRange live_tiles(const CameraBasis& basis, const glm::dvec3& c, double reach, int tile_width, int tile_height);

/// The march kernel's parameters for the scene (first_row left at 0).
MarchParams march_params(const Scene& scene, const Dispatch& dispatch);
/// Lights as the kernel reads them (kernels/shading.cl): positions relative to the camera.
std::vector<cl_float4> light_data(const Scene& scene);

/// The values buffer of program (its kernels' SceneValues), holding scene's literals at the
/// program's value slots; nothing for a program without slots (its kernels get NULL).
std::optional<cl::Buffer> make_scene_values(const PreparedProgram& program, const Scene& scene);
/// Writes scene's literals at the program's value slots into values (made for the same slots).
void write_scene_values(PreparedProgram& program, const Scene& scene, const std::optional<cl::Buffer>& values);
/// Sets kernel argument index, a SceneValues pointer, to values or NULL.
void set_scene_values_arg(cl::Kernel& kernel, int index, const std::optional<cl::Buffer>& values);

/// Bytes of the march kernel's output buffer for dispatch (every plane, kernels/device_types.h).
std::size_t march_output_bytes(const Dispatch& dispatch);
/// The coarse cone pass of a program built with it (uses_cone_pass, kernels/coarse.cl): its kernel
/// and, per block of CLMARCH_COARSE_BLOCK^2 pixels, where the block's rays start and the cone's
/// steps. The march kernel reads the starts (bind_march_inputs).
struct ConePass {
  cl::Kernel kernel;
  Dispatch dispatch;
  std::size_t blocks = 0;
  cl::Buffer starts;
  cl::Buffer steps;
};
/// The cone pass of program for scene (reading values, make_scene_values), or nothing when the
/// scene has none.
std::optional<ConePass> make_cone_pass(const PreparedProgram& program, const Scene& scene,
                                       const std::optional<cl::Buffer>& values);
/// Enqueues the cone pass with params (before the march's chunks, which read its starts).
cl::Event enqueue_cone_pass(cl::CommandQueue& queue, ConePass& cones, const MarchParams& params);
/// One value per block of the cone pass's starts or steps (a blocking read).
std::vector<float> read_cone_plane(cl::CommandQueue& queue, const ConePass& cones, const cl::Buffer& plane);
/// Sets the march kernel's arguments after params: out, lights, the scene's values, and the cone
/// pass's starts when there is one. Returns the index of the next argument.
int bind_march_inputs(cl::Kernel& march, const cl::Buffer& out, const cl::Buffer& lights,
                      const std::optional<cl::Buffer>& values, const std::optional<ConePass>& cones);

/// Enqueues kernel (its argument 0 is params) once per chunk of rows and calls done(first_row, rows,
/// event) after each dispatch was enqueued. Each dispatch writes the program's planes (PreparedProgram::
/// planes) for every pixel of its rows. Polls cancellation between chunks.
void for_each_chunk(cl::CommandQueue& queue, cl::Kernel& kernel, MarchParams params, const Dispatch& dispatch, int height,
                    const std::function<void(int first_row, int rows, const cl::Event& event)>& done);
/// The same for image rows first_row .. end_row - 1 only (a band of a distributed render): first_row
/// must be a multiple of the dispatch's tile height, so that every packet covers the pixels it
/// covers in the whole image.
void for_each_chunk(cl::CommandQueue& queue, cl::Kernel& kernel, MarchParams params, const Dispatch& dispatch,
                    int first_row, int end_row,
                    const std::function<void(int first_row, int rows, const cl::Event& event)>& done);

}  // namespace clmarch
