// OpenCL status names and the DeviceError messages built from them.
#include "cl/cl_errors.hpp"

#include "common/errors.hpp"

#include <fmt/format.h>

namespace clmarch {
namespace {

/// What a status usually means for a render, where that is more than its name says.
const char* status_meaning(int status) {
  switch (status) {
    case CL_MEM_OBJECT_ALLOCATION_FAILURE:
      return "the device ran out of memory";
    case CL_OUT_OF_RESOURCES:
      return "the device ran out of memory or resources, or the kernel faulted";
    case CL_OUT_OF_HOST_MEMORY:
      return "out of host memory";
    case CL_INVALID_BUFFER_SIZE:
      return "a buffer exceeds the device's largest allocation";
    case CL_DEVICE_NOT_AVAILABLE:
      return "the device is busy or switched off";
    case CL_COMPILER_NOT_AVAILABLE:
      return "the driver has no OpenCL C compiler";
    case CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST:
      return "an earlier command failed";
    case kClPlatformNotFoundKhr:
      return "no OpenCL driver is installed";
    default:
      return nullptr;
  }
}

}  // namespace

std::string cl_status_name(int status) {
  switch (status) {
#define CLMARCH_STATUS(name) \
  case name:                 \
    return #name;
    CLMARCH_STATUS(CL_DEVICE_NOT_FOUND)
    CLMARCH_STATUS(CL_DEVICE_NOT_AVAILABLE)
    CLMARCH_STATUS(CL_COMPILER_NOT_AVAILABLE)
    CLMARCH_STATUS(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    CLMARCH_STATUS(CL_OUT_OF_RESOURCES)
    CLMARCH_STATUS(CL_OUT_OF_HOST_MEMORY)
    CLMARCH_STATUS(CL_PROFILING_INFO_NOT_AVAILABLE)
    CLMARCH_STATUS(CL_MEM_COPY_OVERLAP)
    CLMARCH_STATUS(CL_IMAGE_FORMAT_MISMATCH)
    CLMARCH_STATUS(CL_IMAGE_FORMAT_NOT_SUPPORTED)
    CLMARCH_STATUS(CL_BUILD_PROGRAM_FAILURE)
    CLMARCH_STATUS(CL_MAP_FAILURE)
    CLMARCH_STATUS(CL_MISALIGNED_SUB_BUFFER_OFFSET)
    CLMARCH_STATUS(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
    CLMARCH_STATUS(CL_COMPILE_PROGRAM_FAILURE)
    CLMARCH_STATUS(CL_LINKER_NOT_AVAILABLE)
    CLMARCH_STATUS(CL_LINK_PROGRAM_FAILURE)
    CLMARCH_STATUS(CL_INVALID_VALUE)
    CLMARCH_STATUS(CL_INVALID_DEVICE_TYPE)
    CLMARCH_STATUS(CL_INVALID_PLATFORM)
    CLMARCH_STATUS(CL_INVALID_DEVICE)
    CLMARCH_STATUS(CL_INVALID_CONTEXT)
    CLMARCH_STATUS(CL_INVALID_QUEUE_PROPERTIES)
    CLMARCH_STATUS(CL_INVALID_COMMAND_QUEUE)
    CLMARCH_STATUS(CL_INVALID_HOST_PTR)
    CLMARCH_STATUS(CL_INVALID_MEM_OBJECT)
    CLMARCH_STATUS(CL_INVALID_BINARY)
    CLMARCH_STATUS(CL_INVALID_BUILD_OPTIONS)
    CLMARCH_STATUS(CL_INVALID_PROGRAM)
    CLMARCH_STATUS(CL_INVALID_PROGRAM_EXECUTABLE)
    CLMARCH_STATUS(CL_INVALID_KERNEL_NAME)
    CLMARCH_STATUS(CL_INVALID_KERNEL)
    CLMARCH_STATUS(CL_INVALID_ARG_INDEX)
    CLMARCH_STATUS(CL_INVALID_ARG_VALUE)
    CLMARCH_STATUS(CL_INVALID_ARG_SIZE)
    CLMARCH_STATUS(CL_INVALID_KERNEL_ARGS)
    CLMARCH_STATUS(CL_INVALID_WORK_DIMENSION)
    CLMARCH_STATUS(CL_INVALID_WORK_GROUP_SIZE)
    CLMARCH_STATUS(CL_INVALID_WORK_ITEM_SIZE)
    CLMARCH_STATUS(CL_INVALID_GLOBAL_OFFSET)
    CLMARCH_STATUS(CL_INVALID_EVENT_WAIT_LIST)
    CLMARCH_STATUS(CL_INVALID_EVENT)
    CLMARCH_STATUS(CL_INVALID_OPERATION)
    CLMARCH_STATUS(CL_INVALID_BUFFER_SIZE)
    CLMARCH_STATUS(CL_INVALID_GLOBAL_WORK_SIZE)
    CLMARCH_STATUS(CL_INVALID_PROPERTY)
#undef CLMARCH_STATUS
    case kClPlatformNotFoundKhr:
      return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
      return fmt::format("OpenCL error {}", status);
  }
}

std::string device_error_message(const DeviceEntry& device, const cl::Error& error) {
  std::string message =
      fmt::format("OpenCL error on {}: {} failed with {}", device.label(), error.what(), cl_status_name(error.err()));
  if (const char* meaning = status_meaning(error.err())) message.append(" (").append(meaning).append(")");
  // The first line stays one line (device, call, status); the compiler's log follows verbatim.
  if (const auto* build = dynamic_cast<const cl::BuildError*>(&error)) {
    for (const auto& [log_device, log] : build->getBuildLog()) {
      std::string name = device.name;
      try {
        name = log_device.getInfo<CL_DEVICE_NAME>();
      } catch (const cl::Error&) {
      }
      message.append(fmt::format("\nbuild log of {}:\n", name)).append(log);
      while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    }
  }
  return message;
}

void throw_device_error(const DeviceEntry& device, const cl::Error& error) {
  throw DeviceError(device_error_message(device, error));
}

}  // namespace clmarch
