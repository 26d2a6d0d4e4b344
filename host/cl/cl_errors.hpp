// The one place that turns OpenCL API failures into messages.
#pragma once

#include "cl/devices.hpp"

#include <string>

namespace clmarch {

/// clGetPlatformIDs without any installed driver (cl_khr_icd); not in the core headers.
inline constexpr int kClPlatformNotFoundKhr = -1001;

/// Symbolic name of an OpenCL status code ("CL_OUT_OF_RESOURCES").
std::string cl_status_name(int status);

/// "OpenCL error on NAME (PLATFORM): clCall failed with CL_STATUS (what it means)" on the first
/// line; a failed build adds "build log of NAME:" and the log on the lines after.
std::string device_error_message(const DeviceEntry& device, const cl::Error& error);

/// Runs call and turns a cl::Error into DeviceError naming the device and the failing API call;
/// build failures carry the device's build log verbatim.
template <typename Call>
auto with_device_errors(const DeviceEntry& device, Call&& call) -> decltype(call());

[[noreturn]] void throw_device_error(const DeviceEntry& device, const cl::Error& error);

template <typename Call>
auto with_device_errors(const DeviceEntry& device, Call&& call) -> decltype(call()) {
  try {
    return call();
  } catch (const cl::Error& error) {
    throw_device_error(device, error);
  }
}

}  // namespace clmarch
