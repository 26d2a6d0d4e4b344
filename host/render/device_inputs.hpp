// What the march kernel reads besides its program: the per-frame parameters, the lights, the
// values buffer of the scene's literals, and the argument order that binds them.
#pragma once

#include "device_types.h"
#include "render/cone_pass.hpp"
#include "render/dispatch_plan.hpp"
#include "render/prepared_program.hpp"
#include "scene/scene.hpp"

#include <optional>
#include <vector>

namespace clmarch {

/// The march kernel's parameters for the scene (first_row left at 0).
MarchParams march_params(const Scene& scene, const Dispatch& dispatch);
/// Lights as the kernel reads them (kernels/shading.cl): positions relative to the camera.
std::vector<cl_float4> light_data(const Scene& scene);

/// The values buffer of program (its kernels' SceneValues), holding scene's literals at the
/// program's value slots, then its operand grid's data; nothing for a program without either (its
/// kernels get NULL).
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
