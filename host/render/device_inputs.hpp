// What the march kernel reads besides its program: the per-frame parameters, the lights, the
// values buffer of the scene's literals, and the argument order that binds them.
#pragma once

#include "device_types.h"
#include "render/cone_pass.hpp"
#include "render/dispatch_plan.hpp"
#include "render/prepared_program.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace clmarch {

/// The march kernel's parameters for the scene (first_row left at 0).
MarchParams march_params(const Scene& scene, const Dispatch& dispatch);
/// Lights as the kernel reads them (kernels/shading.cl): positions relative to the camera; one
/// unread light for a scene without any (a buffer may not be empty).
std::vector<LightParams> light_data(const Scene& scene);
/// A buffer holding the scene's lights (light_data).
cl::Buffer make_light_buffer(const cl::Context& context, const Scene& scene);
/// Writes the scene's lights into lights, or into a new buffer when there are more of them than it
/// holds (the light count is a frame's number, not the program's).
void write_lights(const cl::CommandQueue& queue, const cl::Context& context, const Scene& scene, cl::Buffer& lights);

/// What one device lets a values buffer take.
struct DeviceMemoryLimits {
  /// "NAME (PLATFORM)".
  std::string device;
  /// CL_DEVICE_MAX_MEM_ALLOC_SIZE: the largest buffer.
  std::uint64_t max_alloc = 0;
  /// CL_DEVICE_MAX_CONSTANT_BUFFER_SIZE: a __constant buffer's limit (at least 64 KiB).
  std::uint64_t max_constant = 0;
};
DeviceMemoryLimits device_memory_limits(const DeviceEntry& device);

/// Empty when a values buffer of bytes fits the device: in global memory with an operand grid, in
/// __constant memory without (sdf_functions' SceneValues); else why, one line naming the limit.
std::string values_buffer_shortfall(std::uint64_t bytes, bool has_grid, const DeviceMemoryLimits& limits);

/// The values buffer of program (its kernels' SceneValues), holding scene's literals at the
/// program's value slots, then its operand grid's data; nothing for a program without either (its
/// kernels get NULL). Throws InputError naming the scene when the device cannot hold it.
std::optional<cl::Buffer> make_scene_values(const PreparedProgram& program, const Scene& scene);
/// Writes scene's literals at the program's value slots and its grid's data into values (made for the
/// same slots), or into a new buffer when the data outgrew it.
void write_scene_values(PreparedProgram& program, const Scene& scene, std::optional<cl::Buffer>& values);
/// Sets kernel argument index, a SceneValues pointer, to values or NULL.
void set_scene_values_arg(cl::Kernel& kernel, int index, const std::optional<cl::Buffer>& values);

/// Sets the march kernel's arguments after params: out, lights, the scene's values, and the cone
/// pass's starts when there is one. Returns the index of the next argument.
int bind_march_inputs(cl::Kernel& march, const cl::Buffer& out, const cl::Buffer& lights,
                      const std::optional<cl::Buffer>& values, const std::optional<ConePass>& cones);

}  // namespace clmarch
