// Assembles the OpenCL C program for one scene: feature switches, the kernels/ building blocks it
// needs (each behind a #line so build errors point at the real file), and the generated scene code.
#pragma once

#include "scene/scene.hpp"

#include <string>

namespace clmarch {

/// What the program is built for.
enum class KernelPurpose {
  /// The march kernel, writing depth and steps only.
  DepthSteps,
  /// The march kernel with normals (no shading).
  Normals,
  /// The march kernel with normals and the lit color.
  Shaded,
  /// The eval_points kernel (tests, throughput ceiling).
  EvalPoints,
};

struct KernelOptions {
  KernelPurpose purpose = KernelPurpose::Shaded;
  /// Pixels per work-item: 1, 4, 8 or 16.
  int lanes = 1;
};

/// The full program source, exactly as it is built (and dumped by --dump-kernel).
std::string generate_kernel_source(const Scene& scene, const KernelOptions& options);

}  // namespace clmarch
