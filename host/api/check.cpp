// Checking a scene against the CPU reference.
#include "api/check.hpp"

#include "reference/reference_renderer.hpp"

namespace clmarch {

CheckOutcome check_scene(const Scene& scene, const SessionOptions& options) {
  OpenClOptions cl;
  cl.device = options.device;
  cl.lanes = options.lanes;
  cl.purpose = KernelPurpose::Buffers;
  CheckOutcome outcome;
  outcome.opencl = render_opencl(scene, cl);
  outcome.reference = render_reference(scene);
  outcome.report =
      cross_check(scene, outcome.opencl.buffers, outcome.reference, reshade_hits(scene, outcome.opencl.buffers));
  return outcome;
}

}  // namespace clmarch
