// Which tiles' centre rays pass near a sphere, per row of tiles in closed form.
#include "render/live_tiles.hpp"

#include <algorithm>
#include <cmath>

namespace clmarch {
namespace {

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
      last = std::min(columns - 1,
                      static_cast<int>(std::floor(tile_position((-b + root) / (2.0 * a), tile_width, columns))) + 1);
      if (first > last) continue;
    }  // a <= 0: g <= 0 beyond some x on a side, or everywhere; the whole row, which is safe
    live.first_column = std::min(live.first_column, first);
    live.last_column = std::max(live.last_column, last);
    live.first_row = std::min(live.first_row, std::max(0, row - 1));
    live.last_row = std::max(live.last_row, std::min(rows - 1, row + 1));
  }
  return live;
}

}  // namespace clmarch
