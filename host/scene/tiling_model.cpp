// The camera's offset in its tiling cell.
#include "scene/tiling_model.hpp"

namespace clmarch {

glm::dvec3 offset_in_cell(const glm::dvec3& position, const glm::dvec3& cell) {
  glm::dvec3 offset = floor_mod(position, cell);
  for (int a = 0; a < 3; ++a) {
    if (!(offset[a] < cell[a]) || offset[a] < 0.0) offset[a] = 0.0;  // rounding can land exactly on the far wall
  }
  return offset;
}

}  // namespace clmarch
