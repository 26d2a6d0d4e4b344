#include "support/evaluate_kernel.hpp"

#include "cl/device_program.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

namespace clmarch::testing {

std::vector<double> run_evaluate_kernel(const std::string& source, const std::vector<double>& in,
                                        std::size_t work_items, std::size_t outputs, bool double_precision) {
  const DeviceProgram program = build_device_program(select_device(std::nullopt), source, kLoggedBuildOptions);
  EXPECT_EQ(compiler_warnings(program.build_log), "") << program.build_log << source;
  const std::size_t scalar = double_precision ? sizeof(double) : sizeof(float);
  std::vector<double> in_double = in;
  std::vector<float> in_float(in.begin(), in.end());
  cl::Buffer input(program.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, in.size() * scalar,
                   double_precision ? static_cast<void*>(in_double.data()) : static_cast<void*>(in_float.data()));
  cl::Buffer output(program.context, CL_MEM_WRITE_ONLY, outputs * scalar);
  cl::Kernel kernel(program.program, "evaluate");
  kernel.setArg(0, input);
  kernel.setArg(1, output);
  program.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(work_items));
  std::vector<double> out(outputs);
  if (double_precision) {
    program.queue.enqueueReadBuffer(output, CL_TRUE, 0, outputs * scalar, out.data());
  } else {
    std::vector<float> out_float(outputs);
    program.queue.enqueueReadBuffer(output, CL_TRUE, 0, outputs * scalar, out_float.data());
    out.assign(out_float.begin(), out_float.end());
  }
  return out;
}

}  // namespace clmarch::testing
