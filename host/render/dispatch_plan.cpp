// Dispatch sizes of tiles, chunks and points, and the loop over a frame's chunks.
#include "render/dispatch_plan.hpp"

#include "common/cancellation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace clmarch {
namespace {

std::size_t round_up(std::size_t n, std::size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

}  // namespace

int packet_width(int lanes) { return CLMARCH_PACKET_WIDTH(lanes); }

Dispatch plan_tile_dispatch(const PreparedProgram& program, int width, int height, std::size_t max_pixels) {
  const std::size_t tile_width = packet_width(program.lanes);
  const std::size_t tile_height = packet_height(program.lanes);
  const std::size_t row_pixels = static_cast<std::size_t>(width);
  const std::size_t rows_allowed =
      std::max<std::size_t>(tile_height, max_pixels / row_pixels / tile_height * tile_height);
  const std::size_t rows = std::min(round_up(static_cast<std::size_t>(height), tile_height), rows_allowed);
  Dispatch d;
  d.local_items = default_local_size(program.program.device);
  d.tile_width = static_cast<int>(tile_width);
  d.tile_height = static_cast<int>(tile_height);
  d.chunk_rows = static_cast<int>(rows);
  const std::size_t packets = round_up(row_pixels, tile_width) / tile_width * (rows / tile_height);
  const std::size_t per_item = static_cast<std::size_t>(program.packets_per_item);
  d.global_items = round_up((packets + per_item - 1) / per_item, d.local_items);
  d.plane_stride = rows * row_pixels;
  return d;
}

Dispatch plan_point_dispatch(const DeviceEntry& device, std::size_t count, int lanes) {
  Dispatch d;
  d.local_items = default_local_size(device);
  d.global_items = round_up((count + lanes - 1) / lanes, d.local_items);
  d.plane_stride = d.global_items * lanes;
  return d;
}

std::size_t chunk_pixels_for(const DeviceEntry& device) {
  constexpr std::size_t kResponsiveChunk = std::size_t{1} << 22;
  const std::size_t bytes_per_pixel = CLMARCH_CHANNEL_COUNT * sizeof(float);
  const std::size_t max_alloc = device.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  const std::size_t global = device.device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>() / 4;
  return std::max<std::size_t>(1, std::min({kResponsiveChunk, max_alloc / bytes_per_pixel, global / bytes_per_pixel}));
}

std::size_t march_output_bytes(const Dispatch& dispatch) {
  return dispatch.plane_stride * CLMARCH_CHANNEL_COUNT * sizeof(float);
}

void for_each_chunk(cl::CommandQueue& queue, cl::Kernel& kernel, MarchParams params, const Dispatch& dispatch,
                    int height, const std::function<void(int first_row, int rows, const cl::Event& event)>& done) {
  for_each_chunk(queue, kernel, params, dispatch, 0, height, done);
}

void for_each_chunk(cl::CommandQueue& queue, cl::Kernel& kernel, MarchParams params, const Dispatch& dispatch,
                    int band_first_row, int end_row,
                    const std::function<void(int first_row, int rows, const cl::Event& event)>& done) {
  if (band_first_row % dispatch.tile_height != 0) {
    throw std::logic_error(fmt::format("for_each_chunk: first row {} is not a multiple of the tile height {}",
                                       band_first_row, dispatch.tile_height));
  }
  for (int first_row = band_first_row; first_row < end_row; first_row += dispatch.chunk_rows) {
    throw_if_cancelled();
    params.first_row = first_row;
    kernel.setArg(0, sizeof(MarchParams), &params);
    cl::Event event;
    queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(dispatch.global_items),
                               cl::NDRange(dispatch.local_items), nullptr, &event);
    done(first_row, std::min(dispatch.chunk_rows, end_row - first_row), event);
  }
}

}  // namespace clmarch
