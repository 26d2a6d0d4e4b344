// The march kernel's dispatch: tiles of packets, chunks of rows, parameters and programs.
#include "render/march_dispatch.hpp"

#include "cl/cl_errors.hpp"
#include "codegen/kernel_source.hpp"
#include "common/cancellation.hpp"
#include "image/atomic_file.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/tiling_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace clmarch {
namespace {

cl_float4 to_cl(const glm::dvec3& v) {
  cl_float4 out;
  out.s[0] = static_cast<float>(v.x);
  out.s[1] = static_cast<float>(v.y);
  out.s[2] = static_cast<float>(v.z);
  out.s[3] = 0.0f;
  return out;
}

std::size_t round_up(std::size_t n, std::size_t multiple) { return (n + multiple - 1) / multiple * multiple; }

/// Tile centres are at (i + 0.5) tile_size: the position of x in tile indices, clamped to
/// [-2, tiles + 1] so that far roots convert safely and stay off the image by more than the one
/// tile of padding.
double tile_position(double x, int tile_size, int tiles) { return std::clamp(x / tile_size - 0.5, -2.0, tiles + 1.0); }

}  // namespace

TileRange live_tiles(const CameraBasis& basis, const glm::dvec3& c, double reach, int tile_width, int tile_height) {
  const int columns = (basis.width + tile_width - 1) / tile_width;
  const int rows = (basis.height + tile_height - 1) / tile_height;
  const TileRange all{0, columns - 1, 0, rows - 1};
  // The kernel rounds c, q and reach^2 to float and its products by an ulp or two: its test can
  // pass a tile whose exact |c x q| exceeds reach |q| by about 1e-6 |c| |q|. A reach wider by
  // 1e-4 (|c| + reach) takes every such tile in, and a tile on each side (columns and rows)
  // covers the rounding of the roots to tiles.
  const double wide = reach + 1e-4 * (glm::length(c) + reach);
  const double k = glm::dot(c, c) - wide * wide;
  if (k <= 0.0) return all;  // the camera is within reach: every ray's line passes near enough
  TileRange live{columns, -1, rows, -1};
  // q(x, y) = P(y) + x D in pixel units (sx = x 2 / width - 1, sy = 1 - y 2 / height), and the
  // tile may meet the sphere where g(x) = k |q|^2 - (c . q)^2 <= 0 (that is |c x q| <= wide |q|).
  const glm::dvec3 d = basis.right_extent * (2.0 / basis.width);
  const double cd = glm::dot(c, d);
  const double a = k * glm::dot(d, d) - cd * cd;
  for (int row = 0; row < rows; ++row) {
    const double y = (row + 0.5) * tile_height;
    const glm::dvec3 p = basis.forward - basis.right_extent + basis.up_extent * (1.0 - y * (2.0 / basis.height));
    const double cp = glm::dot(c, p);
    const double b = 2.0 * (k * glm::dot(p, d) - cp * cd);
    const double c0 = k * glm::dot(p, p) - cp * cp;
    int first = 0, last = columns - 1;
    if (a > 0.0) {
      const double discriminant = b * b - 4.0 * a * c0;
      if (discriminant < 0.0) continue;
      const double root = std::sqrt(discriminant);
      // The tiles whose centre lies between the roots, and one more on each side.
      first = std::max(0, static_cast<int>(std::ceil(tile_position((-b - root) / (2.0 * a), tile_width, columns))) - 1);
      last = std::min(columns - 1, static_cast<int>(std::floor(tile_position((-b + root) / (2.0 * a), tile_width, columns))) + 1);
      if (first > last) continue;
    }  // a <= 0: g <= 0 beyond some x on a side, or everywhere; the whole row, which is safe
    live.first_column = std::min(live.first_column, first);
    live.last_column = std::max(live.last_column, last);
    live.first_row = std::min(live.first_row, std::max(0, row - 1));
    live.last_row = std::max(live.last_row, std::min(rows - 1, row + 1));
  }
  return live;
}

PreparedProgram prepare_program(const Scene& scene, const OpenClOptions& options, KernelPurpose purpose) {
  const DeviceEntry device = select_device(options.device);
  KernelOptions kernel_options{purpose, options.lanes.value_or(default_lanes(device)), options.variant};
  kernel_options.fp_contraction = allows_fp_contraction(device);
  const bool march = purpose != KernelPurpose::EvalPoints;
  if (march) kernel_options.value_slots = options.value_slots;
  const std::string source = generate_kernel_source(scene, kernel_options);
  if (!options.dump_kernel_path.empty()) write_file_atomically(options.dump_kernel_path, source);
  return {build_device_program(device, source, kernel_build_options(options.variant)), kernel_options.lanes,
          march ? packets_per_item(scene, kernel_options.lanes) : 1,
          march ? march_outputs(scene, purpose).planes() : std::vector<int>{}, source, kernel_options};
}

int packet_width(int lanes) { return CLMARCH_PACKET_WIDTH(lanes); }

Dispatch plan_tile_dispatch(const PreparedProgram& program, int width, int height, std::size_t max_pixels) {
  const std::size_t tile_width = packet_width(program.lanes);
  const std::size_t tile_height = packet_height(program.lanes);
  const std::size_t row_pixels = static_cast<std::size_t>(width);
  const std::size_t rows_allowed = std::max<std::size_t>(tile_height, max_pixels / row_pixels / tile_height * tile_height);
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

MarchParams march_params(const Scene& scene, const Dispatch& dispatch) {
  const int width = scene.render.width;
  const int height = scene.render.height;
  const CameraBasis basis = camera_basis(scene.camera, width, height);
  MarchParams params{};
  params.origin = to_cl(basis.origin - map_frame_origin(scene));
  params.forward = to_cl(basis.forward);
  params.right_extent = to_cl(basis.right_extent);
  params.up_extent = to_cl(basis.up_extent);
  params.width = width;
  params.height = height;
  params.chunk_rows = dispatch.chunk_rows;
  params.plane_stride = static_cast<cl_int>(dispatch.plane_stride);
  params.max_steps = scene.render.max_steps;
  params.epsilon = static_cast<float>(scene.render.epsilon);
  params.max_distance = static_cast<float>(scene.render.max_distance);
  params.normal_epsilon = static_cast<float>(scene.render.normal_epsilon);
  if (scene.tiling) params.origin_in_cell = to_cl(offset_in_cell(scene.camera.position, scene.tiling->cell));
  params.camera_height = static_cast<float>(scene.camera.position.y);
  params.over_relaxation = static_cast<float>(camera_over_relaxation(scene));
  params.hit_cone_slope = static_cast<float>(hit_cone_slope(scene.render, scene.camera));
  if (const std::optional<BoundingSphere> bounds = camera_ray_bounds(scene)) {
    const glm::dvec3 c = scene.camera.position - bounds->center;
    params.bounds = to_cl(c);
    params.bounds.s[3] = static_cast<float>(bounds->radius);
    // The rays of a tile are q / |q| with q = f + sx r + sy u, |q| >= 1, where normalising is
    // 1-Lipschitz: they lie within spread of the centre ray's direction, so each passes the centre
    // no nearer than |c x centre| - |c| spread. Beyond reach = radius + |c| spread no ray of the tile
    // meets the sphere; the margin covers the float arithmetic of the test.
    const double spread = dispatch.tile_width / static_cast<double>(width) * glm::length(basis.right_extent) +
                          dispatch.tile_height / static_cast<double>(height) * glm::length(basis.up_extent);
    const double distance = glm::length(c);
    const double reach = bounds->radius + distance * spread + 1e-5 * (distance + bounds->radius);
    params.tile_reach.s[0] = static_cast<float>(reach * reach);
    const TileRange live = live_tiles(basis, c, reach, dispatch.tile_width, dispatch.tile_height);
    params.live_columns[0] = live.first_column;
    params.live_columns[1] = live.last_column;
    params.live_rows[0] = live.first_row;
    params.live_rows[1] = live.last_row;
  }
  return params;
}

std::vector<cl_float4> light_data(const Scene& scene) {
  std::vector<cl_float4> data;
  for (const Light& light : scene.lights) {
    cl_float4 where = light.kind == LightKind::Point ? to_cl(light.position - scene.camera.position) : to_cl(light.direction);
    where.s[3] = light.kind == LightKind::Point ? 1.0f : 0.0f;
    data.push_back(where);
    data.push_back(to_cl(light.color * light.intensity));
  }
  if (data.empty()) data.push_back(to_cl(glm::dvec3(0.0)));  // a buffer may not be empty
  return data;
}

std::optional<cl::Buffer> make_scene_values(const PreparedProgram& program, const Scene& scene) {
  std::vector<float> values = scene_values(scene, program.kernel_options);
  if (values.empty()) return std::nullopt;
  return cl::Buffer(program.program.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, values.size() * sizeof(float),
                    values.data());
}

void write_scene_values(PreparedProgram& program, const Scene& scene, const std::optional<cl::Buffer>& values) {
  if (!values) return;
  const std::vector<float> data = scene_values(scene, program.kernel_options);
  program.program.queue.enqueueWriteBuffer(*values, CL_TRUE, 0, data.size() * sizeof(float), data.data());
}

void set_scene_values_arg(cl::Kernel& kernel, int index, const std::optional<cl::Buffer>& values) {
  if (values) {
    kernel.setArg(index, *values);
  } else {
    kernel.setArg(index, sizeof(cl_mem), nullptr);  // a NULL pointer: the program spells every literal
  }
}

std::size_t march_output_bytes(const Dispatch& dispatch) {
  return dispatch.plane_stride * CLMARCH_CHANNEL_COUNT * sizeof(float);
}

std::optional<ConePass> make_cone_pass(const PreparedProgram& program, const Scene& scene,
                                       const std::optional<cl::Buffer>& values) {
  if (!uses_cone_pass(scene)) return std::nullopt;
  const DeviceProgram& dp = program.program;
  ConePass cones;
  cones.blocks = static_cast<std::size_t>(CLMARCH_COARSE_BLOCKS(scene.render.width)) * CLMARCH_COARSE_BLOCKS(scene.render.height);
  cones.dispatch = plan_point_dispatch(dp.device, cones.blocks, program.lanes);
  // The kernel stores whole vectors of lanes, padding included.
  const std::size_t bytes = cones.dispatch.plane_stride * sizeof(float);
  cones.starts = cl::Buffer(dp.context, CL_MEM_READ_WRITE, bytes);
  cones.steps = cl::Buffer(dp.context, CL_MEM_WRITE_ONLY | CL_MEM_HOST_READ_ONLY, bytes);
  cones.kernel = cl::Kernel(dp.program, "coarse_cones");
  cones.kernel.setArg(1, cones.starts);
  cones.kernel.setArg(2, cones.steps);
  set_scene_values_arg(cones.kernel, 3, values);
  return cones;
}

cl::Event enqueue_cone_pass(cl::CommandQueue& queue, ConePass& cones, const MarchParams& params) {
  cones.kernel.setArg(0, sizeof(MarchParams), &params);
  cl::Event event;
  queue.enqueueNDRangeKernel(cones.kernel, cl::NullRange, cl::NDRange(cones.dispatch.global_items),
                             cl::NDRange(cones.dispatch.local_items), nullptr, &event);
  return event;
}

std::vector<float> read_cone_plane(cl::CommandQueue& queue, const ConePass& cones, const cl::Buffer& plane) {
  std::vector<float> values(cones.blocks);
  queue.enqueueReadBuffer(plane, CL_TRUE, 0, values.size() * sizeof(float), values.data());
  return values;
}

int bind_march_inputs(cl::Kernel& march, const cl::Buffer& out, const cl::Buffer& lights,
                      const std::optional<cl::Buffer>& values, const std::optional<ConePass>& cones) {
  march.setArg(1, out);
  march.setArg(2, lights);
  set_scene_values_arg(march, 3, values);
  if (!cones) return 4;
  march.setArg(4, cones->starts);
  return 5;
}

void for_each_chunk(cl::CommandQueue& queue, cl::Kernel& kernel, MarchParams params, const Dispatch& dispatch, int height,
                    const std::function<void(int first_row, int rows, const cl::Event& event)>& done) {
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
    queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(dispatch.global_items), cl::NDRange(dispatch.local_items),
                               nullptr, &event);
    done(first_row, std::min(dispatch.chunk_rows, end_row - first_row), event);
  }
}

}  // namespace clmarch
