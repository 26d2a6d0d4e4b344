// Program building. A process reuses its own programs (build_device_program); across processes the
// driver's cache keyed by source, device and options serves repeated builds (PoCL:
// ~/.cache/pocl/kcache); docs/performance.md has the measured first and second times.
#include "cl/device_program.hpp"

#include "cl/build_cache.hpp"
#include "cl/cl_errors.hpp"
#include "common/cancellation.hpp"
#include "common/log.hpp"

#include <fmt/format.h>

#include <chrono>
#include <list>
#include <mutex>
#include <optional>
#include <vector>

namespace clmarch {

namespace {

/// A device's context and queue, made once per process.
struct DeviceQueue {
  cl_device_id id = nullptr;
  cl::Context context;
  cl::CommandQueue queue;
};

/// A built program and what it was built from.
struct KeptProgram {
  cl_device_id device = nullptr;
  std::string options;
  std::string source;
  cl::Program program;
  std::string build_log;
};

/// The process's device queues and kept programs (most recently used last). One mutex: builds of
/// different programs from several threads are serialised, which PoCL's compiler is anyway.
struct ProgramStore {
  std::mutex mutex;
  std::vector<DeviceQueue> queues;
  std::list<KeptProgram> programs;
  /// Programs compiled (not found among the kept ones) since the process started.
  std::uint64_t compiled = 0;
};

ProgramStore& program_store() {
  static ProgramStore store;
  return store;
}

const DeviceQueue& device_queue(ProgramStore& store, const DeviceEntry& device) {
  for (const DeviceQueue& q : store.queues) {
    if (q.id == device.device()) return q;
  }
  DeviceQueue q;
  q.id = device.device();
  q.context = cl::Context(device.device);
  q.queue = cl::CommandQueue(q.context, device.device, CL_QUEUE_PROFILING_ENABLE);
  store.queues.push_back(std::move(q));
  return store.queues.back();
}

void log_build(const DeviceEntry& device, const std::string& options) {
  log_verbose(fmt::format("device {}, {}, build options '{}'", device.label(),
                          device.is_gpu   ? "GPU"
                          : device.is_cpu ? "CPU"
                                          : "other",
                          options));
}

/// Builds the program, logging its time, its log and (--verbose) the driver's cache.
void build_logged(const DeviceEntry& device, const std::string& options, DeviceProgram& out) {
  log_build(device, options);
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
}

}  // namespace

DeviceProgram build_device_program(const DeviceEntry& device, const std::string& source, const std::string& options) {
  return with_device_errors(device, [&] {
    ProgramStore& store = program_store();
    const std::lock_guard<std::mutex> lock(store.mutex);
    DeviceProgram out;
    out.device = device;
    const DeviceQueue& queue = device_queue(store, device);
    out.context = queue.context;
    out.queue = queue.queue;
    for (auto kept = store.programs.begin(); kept != store.programs.end(); ++kept) {
      if (kept->device == device.device() && kept->options == options && kept->source == source) {
        log_verbose(fmt::format("program kept from an earlier build of this process, on {}", device.label()));
        out.program = kept->program;
        out.build_log = kept->build_log;
        store.programs.splice(store.programs.end(), store.programs, kept);
        return out;
      }
    }
    out.program = cl::Program(out.context, source);
    build_logged(device, options, out);
    ++store.compiled;
    store.programs.push_back({device.device(), options, source, out.program, out.build_log});
    if (store.programs.size() > kKeptPrograms) store.programs.pop_front();
    return out;
  });
}

void forget_device_programs() {
  ProgramStore& store = program_store();
  const std::lock_guard<std::mutex> lock(store.mutex);
  store.programs.clear();
}

std::uint64_t device_programs_compiled() {
  ProgramStore& store = program_store();
  const std::lock_guard<std::mutex> lock(store.mutex);
  return store.compiled;
}

double event_milliseconds(const cl::Event& event) {
  const cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  const cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return static_cast<double>(end - start) * 1e-6;
}

}  // namespace clmarch
