// Device enumeration through the ICD loader.
#include "cl/devices.hpp"

#include "common/errors.hpp"

#include <fmt/format.h>

#include <cstdlib>

namespace clmarch {

std::string DeviceEntry::label() const { return fmt::format("{} ({})", name, platform_name); }

std::vector<DeviceEntry> list_devices() {
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    return {};  // clGetPlatformIDs fails with CL_PLATFORM_NOT_FOUND_KHR when no ICD is installed
  }
  std::vector<DeviceEntry> entries;
  for (const cl::Platform& platform : platforms) {
    std::vector<cl::Device> devices;
    try {
      platform.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform without devices
    }
    for (const cl::Device& device : devices) {
      DeviceEntry entry;
      entry.index = static_cast<int>(entries.size());
      entry.platform = platform;
      entry.device = device;
      entry.platform_name = platform.getInfo<CL_PLATFORM_NAME>();
      entry.name = device.getInfo<CL_DEVICE_NAME>();
      const cl_device_type type = device.getInfo<CL_DEVICE_TYPE>();
      entry.is_gpu = (type & CL_DEVICE_TYPE_GPU) != 0;
      entry.is_cpu = (type & CL_DEVICE_TYPE_CPU) != 0;
      entries.push_back(std::move(entry));
    }
  }
  return entries;
}

std::string no_device_message() {
  return "no OpenCL platform or device found (clGetPlatformIDs, clGetDeviceIDs); install an OpenCL driver such as "
         "pocl-opencl-icd";
}

DeviceEntry select_device(std::optional<int> index) {
  const std::vector<DeviceEntry> devices = list_devices();
  if (devices.empty()) throw DeviceError(no_device_message());
  if (index) {
    if (*index < 0 || *index >= static_cast<int>(devices.size())) {
      throw InputError(
          fmt::format("--device {}: no such device (there are {}: see `clmarch devices`)", *index, devices.size()));
    }
    return devices[static_cast<std::size_t>(*index)];
  }
  for (const DeviceEntry& d : devices) {
    if (d.is_gpu) return d;
  }
  for (const DeviceEntry& d : devices) {
    if (d.is_cpu) return d;
  }
  return devices.front();
}

int default_lanes(const DeviceEntry& device) { return device.is_gpu ? 1 : 16; }

bool DeviceEntry::is_pocl() const { return platform_name == "Portable Computing Language"; }

bool DeviceEntry::has_fp64() const {
  return device.getInfo<CL_DEVICE_EXTENSIONS>().find("cl_khr_fp64") != std::string::npos;
}

bool allows_fp_contraction(const DeviceEntry& device) { return device.is_pocl(); }

std::size_t default_local_size(const DeviceEntry& device) { return device.is_gpu ? 64 : 8; }

void pin_pocl_threads_for_timing() { setenv("POCL_AFFINITY", "1", /*overwrite=*/0); }

}  // namespace clmarch
