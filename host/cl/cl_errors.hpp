// The one place that turns OpenCL API failures into messages.
#pragma once

#include "cl/devices.hpp"

#include <string>

namespace clmarch {

/// Symbolic name of an OpenCL status code ("CL_OUT_OF_RESOURCES").
std::string cl_status_name(int status);

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
