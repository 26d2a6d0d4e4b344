// Program building. The driver's own cache keyed by source, device and options serves repeated
// builds (PoCL: ~/.cache/pocl/kcache); docs/performance.md has the measured first and second times.
#include "cl/device_program.hpp"

#include "cl/cl_errors.hpp"

#include <chrono>

namespace clmarch {

DeviceProgram build_device_program(const DeviceEntry& device, const std::string& source) {
  return with_device_errors(device, [&] {
    DeviceProgram out;
    out.device = device;
    out.context = cl::Context(device.device);
    out.queue = cl::CommandQueue(out.context, device.device, CL_QUEUE_PROFILING_ENABLE);
    out.program = cl::Program(out.context, source);
    const auto start = std::chrono::steady_clock::now();
    out.program.build(std::vector<cl::Device>{device.device}, "-cl-std=CL1.2");
    out.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    out.build_log = out.program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device.device);
    return out;
  });
}

double event_milliseconds(const cl::Event& event) {
  const cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  const cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return static_cast<double>(end - start) * 1e-6;
}

}  // namespace clmarch
