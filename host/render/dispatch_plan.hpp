// How the kernels are dispatched: the march kernel over tiles of packets in chunks of rows, a
// point kernel over its points. Shared by the renderer and the benchmark's recording march, so
// both run the kernel exactly alike.
#pragma once

#include "cl/devices.hpp"
#include "device_types.h"
#include "render/prepared_program.hpp"

#include <cstddef>
#include <functional>

namespace clmarch {

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
/// Bytes of the march kernel's output buffer for dispatch (every plane, kernels/device_types.h).
std::size_t march_output_bytes(const Dispatch& dispatch);

/// Enqueues kernel (its argument 0 is params) once per chunk of rows and calls done(first_row, rows,
/// event) after each dispatch was enqueued. Each dispatch writes the program's planes (PreparedProgram::
/// planes) for every pixel of its rows. Polls cancellation between chunks.
void for_each_chunk(cl::CommandQueue& queue, cl::Kernel& kernel, MarchParams params, const Dispatch& dispatch,
                    int height, const std::function<void(int first_row, int rows, const cl::Event& event)>& done);
/// The same for image rows first_row .. end_row - 1 only (a band of a distributed render): first_row
/// must be a multiple of the dispatch's tile height, so that every packet covers the pixels it
/// covers in the whole image.
void for_each_chunk(cl::CommandQueue& queue, cl::Kernel& kernel, MarchParams params, const Dispatch& dispatch,
                    int first_row, int end_row,
                    const std::function<void(int first_row, int rows, const cl::Event& event)>& done);

}  // namespace clmarch
