// The CPU reference's glsl node: the user's code run by the interpreter (glsl/glsl_interpreter),
// never through its OpenCL translation, so that a difference between the renderers is a
// translation bug.
#include "reference/reference_sdf.hpp"

namespace clmarch {

double sd_glsl(const glm::dvec3& p, const Glsl& params) {
  return params.program->interpreter->distance(p, params.program->time) / params.lipschitz;
}

}  // namespace clmarch
