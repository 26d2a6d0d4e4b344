// The coarse cone pass (render.coarse_pass: cone) in double precision: the reference of
// kernels/coarse.cl, written from the rule in docs/scene-format.md.
#pragma once

#include "scene/scene.hpp"

#include <optional>
#include <vector>

namespace clmarch {

/// Per block of CLMARCH_COARSE_BLOCK x CLMARCH_COARSE_BLOCK pixels (row-major, blocks_x per row):
/// the depth where the block's camera rays start their own march, and the cone's steps.
struct ConeStarts {
  int blocks_x = 0;
  std::vector<double> start;
  std::vector<int> steps;

  /// The start of pixel (i, j)'s block.
  double at_pixel(int i, int j) const;
};

/// The cone pass of scene (uses_cone_pass(scene) must hold).
ConeStarts reference_cone_starts(const Scene& scene);
/// reference_cone_starts(scene) when the scene uses the cone pass, nothing otherwise.
std::optional<ConeStarts> reference_cones_if_used(const Scene& scene);

}  // namespace clmarch
