// A built OpenCL program on one device, with an in-order profiling queue.
#pragma once

#include "cl/devices.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

namespace clmarch {

/// Options of every build: OpenCL C 1.2, which every driver we target compiles.
inline constexpr const char* kBuildOptions = "-cl-std=CL1.2";

struct DeviceProgram {
  DeviceEntry device;
  cl::Context context;
  cl::CommandQueue queue;
  cl::Program program;
  /// Wall time of clBuildProgram; small when the driver's cache (PoCL's kcache) already holds it.
  double build_ms = 0.0;
  /// The device compiler's messages for a successful build (warnings are bugs: tests keep it clean).
  std::string build_log;
};

/// Builds source for the device with options (kBuildOptions and more). Throws DeviceError with the
/// build log on failure. With --verbose it logs the device, the options, the build time and the
/// driver cache.
///
/// A process keeps one context and queue per device, and the programs it built last (at most
/// kKeptPrograms, the least recently used dropped first): building the same source with the same
/// options again returns the kept program with build_ms 0, so the renderers of a long-lived process
/// (frames, a sweep, a test executable's tests) share contexts and programs.
DeviceProgram build_device_program(const DeviceEntry& device, const std::string& source,
                                   const std::string& options = kBuildOptions);

/// Programs build_device_program keeps for reuse.
inline constexpr std::size_t kKeptPrograms = 32;

/// Drops the kept programs (their contexts stay); later builds compile again.
void forget_device_programs();

/// Programs build_device_program compiled in this process (those it found kept not counted):
/// what a session's or a sweep's builds are measured by.
std::uint64_t device_programs_compiled();

/// Milliseconds between the start and end of a profiled event.
double event_milliseconds(const cl::Event& event);

}  // namespace clmarch
