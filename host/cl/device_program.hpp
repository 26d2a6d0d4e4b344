// A built OpenCL program on one device, with an in-order profiling queue.
#pragma once

#include "cl/devices.hpp"

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
DeviceProgram build_device_program(const DeviceEntry& device, const std::string& source,
                                   const std::string& options = kBuildOptions);

/// Milliseconds between the start and end of a profiled event.
double event_milliseconds(const cl::Event& event);

}  // namespace clmarch
