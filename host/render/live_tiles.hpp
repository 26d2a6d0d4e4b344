// The tiles of an image that may see the scene's bounding sphere: the march kernel skips the
// others by integer comparisons (MarchParams::live_columns, live_rows).
#pragma once

#include "scene/camera_model.hpp"

#include <glm/glm.hpp>

namespace clmarch {

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

}  // namespace clmarch
