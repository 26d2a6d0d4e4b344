// Building and running a test's `evaluate` kernel: real inputs in, real outputs back, in float or
// double, as the GLSL translation tests evaluate the translated code on the device.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace clmarch::testing {

/// Builds source on the default device (no compiler warning allowed: a failed expectation) and runs
/// its kernel `evaluate(global const real* in, global real* out)` over work_items work-items,
/// real being double where double_precision, else float (in is rounded to it); returns `outputs`
/// values of out.
std::vector<double> run_evaluate_kernel(const std::string& source, const std::vector<double>& in,
                                        std::size_t work_items, std::size_t outputs, bool double_precision);

}  // namespace clmarch::testing
