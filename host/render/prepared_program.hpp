// The program of one purpose, generated for a scene and built for its device: what every dispatch
// of the renderer and the benchmarks starts from.
#pragma once

#include "cl/device_program.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

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
  /// program_key(scene, kernel_options): which scenes it renders.
  ProgramKey key;
  /// Whether every literal of the scene's code is read from the values buffer (render.literals).
  bool literals_in_buffer = false;
  /// Whether its march kernels call their stages (render.stages, kernels/lanes.cl).
  bool stages_called = false;
};

/// The program variant the scene renders with: variant, in double where the scene asks for
/// render.precision: double.
KernelVariant scene_variant(const Scene& scene, KernelVariant variant);

/// Throws InputError naming the scene file and the device where a double program cannot run: the
/// device lacks cl_khr_fp64.
void check_precision_support(const Scene& scene, const KernelVariant& variant, const std::string& device,
                             bool has_fp64);

/// Whether the program reads every literal of the scene's code from its values buffer: a code with
/// literals and render.literals: buffer, or auto where the caller asked (OpenClOptions::
/// literals_in_buffer); inline spells them.
bool literals_in_buffer(const Scene& scene, const KernelOptions& kernel_options, bool asked);

/// Generates and builds the scene's program for purpose (handing the source to
/// options.before_build first when set).
PreparedProgram prepare_program(const Scene& scene, const OpenClOptions& options, KernelPurpose purpose);

}  // namespace clmarch
