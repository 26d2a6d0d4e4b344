// Program building. The driver's own cache keyed by source, device and options serves repeated
// builds (PoCL: ~/.cache/pocl/kcache); docs/performance.md has the measured first and second times.
#include "cl/device_program.hpp"

#include "cl/build_cache.hpp"
#include "cl/cl_errors.hpp"
#include "common/cancellation.hpp"
#include "common/log.hpp"

#include <fmt/format.h>

#include <chrono>
#include <optional>

namespace clmarch {

DeviceProgram build_device_program(const DeviceEntry& device, const std::string& source, const std::string& options) {
  return with_device_errors(device, [&] {
    DeviceProgram out;
    out.device = device;
    out.context = cl::Context(device.device);
    out.queue = cl::CommandQueue(out.context, device.device, CL_QUEUE_PROFILING_ENABLE);
    out.program = cl::Program(out.context, source);
    log_verbose(fmt::format("device {}, {}, build options '{}'", device.label(),
                            device.is_gpu   ? "GPU"
                            : device.is_cpu ? "CPU"
                                            : "other",
                            options));
    const bool probe_cache = verbosity() == Verbosity::Verbose;
    std::optional<BuildCacheProbe> probe;
    if (probe_cache) probe.emplace(device);
    const auto start = std::chrono::steady_clock::now();
    {
      const BlockingCall uninterruptible_build;
      out.program.build(std::vector<cl::Device>{device.device}, options.c_str());
    }
    out.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    out.build_log = out.program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device.device);
    // A successful build may still carry the compiler's warnings; shown verbatim, as on failure.
    const std::size_t log_end = out.build_log.find_last_not_of(" \t\r\n");
    if (log_end != std::string::npos) {
      log_verbose(fmt::format("build log of {}:\n{}", device.name, out.build_log.substr(0, log_end + 1)));
    }
    if (probe) {
      const BuildCache cache = probe->result();
      std::string where;
      if (!probe->folder().empty()) where = fmt::format(" ({})", probe->folder().string());
      log_verbose(fmt::format("build {:.0f} ms, driver cache {}{}", out.build_ms,
                              kBuildCacheNames[static_cast<int>(cache)], where));
    }
    return out;
  });
}

double event_milliseconds(const cl::Event& event) {
  const cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  const cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return static_cast<double>(end - start) * 1e-6;
}

}  // namespace clmarch
