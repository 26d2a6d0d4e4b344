// The march kernel's parameters, lights and values, and how they are bound to its arguments.
#include "render/device_inputs.hpp"

#include "codegen/kernel_source.hpp"
#include "common/available_memory.hpp"
#include "common/errors.hpp"
#include "render/live_tiles.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/scene_box.hpp"
#include "scene/tiling_model.hpp"

#include <fmt/format.h>

#include <cmath>

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

/// Writes v's x, y, z to the camera doubles from first on (CLMARCH_CAMERA_*).
void set_camera_double(MarchParams& params, int first, const glm::dvec3& v) {
  for (int axis = 0; axis < 3; ++axis) params.camera_double[first + axis] = v[axis];
}

/// The shading's numbers as the kernels read them (kernels/device_types.h, ShadingParams); those of
/// parts the scene lacks stay 0.
ShadingParams shading_params(const Scene& scene) {
  const Shading& s = scene.shading;
  ShadingParams p{};
  p.background = to_cl(s.background);
  p.ambient = to_cl(s.ambient);
  p.diffuse = static_cast<float>(s.diffuse);
  p.step_ao = static_cast<float>(s.step_ao);
  if (s.fog) {
    p.fog_color = to_cl(s.fog->color);
    p.fog_density = static_cast<float>(s.fog->density);
  }
  if (s.shadows) {
    p.shadow_k = static_cast<float>(s.shadows->k);
    p.shadow_min_t = static_cast<float>(s.shadows->min_t);
    p.shadow_max_t = static_cast<float>(s.shadows->max_t);
    p.shadow_max_steps = s.shadows->max_steps;
  }
  if (s.ambient_occlusion) {
    p.ao_samples = s.ambient_occlusion->samples;
    p.ao_step = static_cast<float>(s.ambient_occlusion->step);
    p.ao_power = static_cast<float>(s.ambient_occlusion->power);
  }
  p.reflection_bounces = s.reflection_bounces;
  p.reflection_offset = static_cast<float>(reflection_offset(scene.render));
  if (s.sky) {
    p.sky_horizon = to_cl(s.sky->horizon);
    p.sky_zenith = to_cl(s.sky->zenith);
  }
  if (s.glow) {
    p.glow_color = to_cl(s.glow->color);
    p.glow_radius = static_cast<float>(s.glow->radius);
  }
  if (s.planetary_glow) {
    p.planet_glow_color = to_cl(s.planetary_glow->color);
    p.planet_glow_sharpness = static_cast<float>(s.planetary_glow->sharpness);
    p.planet_glow_sun = to_cl(s.planetary_glow->sun_direction);
  }
  if (s.height_fog) {
    const HeightFog& f = *s.height_fog;
    p.height_fog_density = static_cast<float>(f.density);
    p.height_fog_falloff = static_cast<float>(f.falloff);
    p.height_fog_color = to_cl(f.color);
    p.height_fog_sun_color = to_cl(f.sun_color);
    p.height_fog_sun_direction = to_cl(f.sun_direction);
    p.height_fog_sun_power = static_cast<float>(f.sun_power);
  }
  p.gamma = static_cast<float>(s.gamma);
  p.light_count = static_cast<cl_int>(scene.lights.size());
  return p;
}

}  // namespace

MarchParams march_params(const Scene& scene, const Dispatch& dispatch) {
  const int width = scene.render.width;
  const int height = scene.render.height;
  const CameraBasis basis = camera_basis(scene.camera, width, height);
  MarchParams params{};
  params.origin = to_cl(basis.origin - map_frame_origin(scene));
  params.forward = to_cl(basis.forward);
  params.right_extent = to_cl(basis.right_extent);
  params.up_extent = to_cl(basis.up_extent);
  set_camera_double(params, CLMARCH_CAMERA_ORIGIN, basis.origin - map_frame_origin(scene));
  set_camera_double(params, CLMARCH_CAMERA_FORWARD, basis.forward);
  set_camera_double(params, CLMARCH_CAMERA_RIGHT, basis.right_extent);
  set_camera_double(params, CLMARCH_CAMERA_UP, basis.up_extent);
  params.width = width;
  params.height = height;
  params.chunk_rows = dispatch.chunk_rows;
  params.plane_stride = static_cast<cl_int>(dispatch.plane_stride);
  params.max_steps = scene.render.max_steps;
  params.epsilon = static_cast<float>(scene.render.epsilon);
  params.max_distance = static_cast<float>(scene.render.max_distance);
  params.normal_epsilon = static_cast<float>(scene.render.normal_epsilon);
  if (scene.tiling) {
    const glm::dvec3 in_cell = offset_in_cell(scene.camera.position, scene.tiling->cell);
    params.origin_in_cell = to_cl(in_cell);
    set_camera_double(params, CLMARCH_CAMERA_ORIGIN_IN_CELL, in_cell);
  }
  params.camera_height = static_cast<float>(scene.camera.position.y);
  params.over_relaxation = static_cast<float>(camera_over_relaxation(scene));
  params.hit_cone_slope = static_cast<float>(hit_cone_slope(scene.render, scene.camera));
  params.shading = shading_params(scene);
  if (const std::optional<BoundingSphere> bounds = camera_ray_bounds(scene)) {
    const glm::dvec3 c = scene.camera.position - bounds->center;
    params.bounds = to_cl(c);
    params.bounds.s[3] = static_cast<float>(bounds->radius);
    params.bounds_gain.s[0] = static_cast<float>(bounds->gain);
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
  if (const std::optional<BoundingBox> box = camera_ray_box(scene)) {
    params.box_low = to_cl(box->low - scene.camera.position);
    params.box_low.s[3] = 1.0f;
    params.box_high = to_cl(box->high - scene.camera.position);
    params.bounds_gain.s[1] = static_cast<float>(box->gain);
  }
  if (const std::optional<BoundingSphere> bounds = cell_bounds(scene)) {
    params.cell_bounds = to_cl(bounds->center);
    params.cell_bounds.s[3] = static_cast<float>(bounds->radius);
  }
  return params;
}

static_assert(static_cast<int>(LightKind::Point) == CLMARCH_LIGHT_POINT &&
                  static_cast<int>(LightKind::Directional) == CLMARCH_LIGHT_DIRECTIONAL &&
                  static_cast<int>(LightKind::Spot) == CLMARCH_LIGHT_SPOT,
              "LightKind and the kernels' CLMARCH_LIGHT_* agree");
static_assert(static_cast<int>(Falloff::None) == CLMARCH_FALLOFF_NONE &&
                  static_cast<int>(Falloff::InverseSquare) == CLMARCH_FALLOFF_INVERSE_SQUARE,
              "Falloff and the kernels' CLMARCH_FALLOFF_* agree");

std::vector<LightParams> light_data(const Scene& scene) {
  std::vector<LightParams> data;
  for (const Light& light : scene.lights) {
    LightParams params{};
    params.kind = static_cast<cl_int>(light.kind);
    params.where =
        light.kind == LightKind::Directional ? to_cl(light.direction) : to_cl(light.position - scene.camera.position);
    params.radiance = to_cl(light.color * light.intensity);
    params.spot_axis = to_cl(light.axis);
    params.falloff = static_cast<cl_int>(light.falloff);
    params.casts_shadows = light.shadows ? 1 : 0;
    params.inverse_range2 = light.range ? static_cast<float>(1.0 / (*light.range * *light.range)) : 0.0f;
    params.cos_inner = static_cast<float>(std::cos(glm::radians(light.inner_angle)));
    params.cos_outer = static_cast<float>(std::cos(glm::radians(light.outer_angle)));
    data.push_back(params);
  }
  if (data.empty()) data.push_back(LightParams{});  // a buffer may not be empty
  return data;
}

cl::Buffer make_light_buffer(const cl::Context& context, const Scene& scene) {
  std::vector<LightParams> lights = light_data(scene);
  return cl::Buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, lights.size() * sizeof(LightParams),
                    lights.data());
}

void write_lights(const cl::CommandQueue& queue, const cl::Context& context, const Scene& scene, cl::Buffer& lights) {
  const std::vector<LightParams> data = light_data(scene);
  if (data.size() * sizeof(LightParams) > lights.getInfo<CL_MEM_SIZE>()) {
    lights = make_light_buffer(context, scene);
    return;
  }
  queue.enqueueWriteBuffer(lights, CL_TRUE, 0, data.size() * sizeof(LightParams), data.data());
}

namespace {

/// Writes values into buffer from where they are: the slots, then the grid's data straight from
/// the grid's cache (a copy of half a gigabyte for a million operands saved).
void write_program_values(const cl::CommandQueue& queue, const cl::Buffer& buffer, const ProgramValues& values) {
  const std::size_t slot_bytes = values.slots.size() * sizeof(float);
  if (slot_bytes > 0) queue.enqueueWriteBuffer(buffer, CL_TRUE, 0, slot_bytes, values.slots.data());
  if (values.data && !values.data->empty()) {
    queue.enqueueWriteBuffer(buffer, CL_TRUE, slot_bytes, values.data->size() * sizeof(float), values.data->data());
  }
}

}  // namespace

DeviceMemoryLimits device_memory_limits(const DeviceEntry& device) {
  return {device.label(), device.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>(),
          device.device.getInfo<CL_DEVICE_MAX_CONSTANT_BUFFER_SIZE>()};
}

std::string values_buffer_shortfall(std::uint64_t bytes, bool has_grid, const DeviceMemoryLimits& limits) {
  const std::uint64_t limit = has_grid ? limits.max_alloc : limits.max_constant;
  if (bytes <= limit) return {};
  return fmt::format(
      "the scene's values buffer ({}) needs {}, but the device {} allows at most {} bytes ({})",
      has_grid ? "its changing literals and its operand grid" : "its changing literals, in __constant memory",
      bytes_and_gibibytes(bytes), limits.device, limit,
      has_grid ? "CL_DEVICE_MAX_MEM_ALLOC_SIZE" : "CL_DEVICE_MAX_CONSTANT_BUFFER_SIZE");
}

std::optional<cl::Buffer> make_scene_values(const PreparedProgram& program, const Scene& scene) {
  const ProgramValues values = scene_values(scene, program.kernel_options);
  if (values.size() == 0) return std::nullopt;
  const std::string shortfall = values_buffer_shortfall(values.size() * sizeof(float), values.data != nullptr,
                                                        device_memory_limits(program.program.device));
  if (!shortfall.empty()) throw InputError(fmt::format("{}: {}", scene.source_name, shortfall));
  cl::Buffer buffer(program.program.context, CL_MEM_READ_ONLY, values.size() * sizeof(float));
  write_program_values(program.program.queue, buffer, values);
  return buffer;
}

void write_scene_values(PreparedProgram& program, const Scene& scene, std::optional<cl::Buffer>& values) {
  if (!values) return;
  const ProgramValues data = scene_values(scene, program.kernel_options);
  // An operand grid's data changes size with the frame's scene: a larger one takes a new buffer.
  if (data.size() * sizeof(float) > values->getInfo<CL_MEM_SIZE>()) {
    values = make_scene_values(program, scene);
    return;
  }
  write_program_values(program.program.queue, *values, data);
}

void set_scene_values_arg(cl::Kernel& kernel, int index, const std::optional<cl::Buffer>& values) {
  if (values) {
    kernel.setArg(index, *values);
  } else {
    kernel.setArg(index, sizeof(cl_mem), nullptr);  // a NULL pointer: the program spells every literal
  }
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

}  // namespace clmarch
