// OpenCL status names and the DeviceError messages built from them.
#include "cl/cl_errors.hpp"

#include "common/errors.hpp"

#include <fmt/format.h>

namespace clmarch {

std::string cl_status_name(int status) {
  switch (status) {
#define CLMARCH_STATUS(name) case name: return #name;
    CLMARCH_STATUS(CL_DEVICE_NOT_FOUND)
    CLMARCH_STATUS(CL_DEVICE_NOT_AVAILABLE)
    CLMARCH_STATUS(CL_COMPILER_NOT_AVAILABLE)
    CLMARCH_STATUS(CL_MEM_OBJECT_ALLOCATION_FAILURE)
    CLMARCH_STATUS(CL_OUT_OF_RESOURCES)
    CLMARCH_STATUS(CL_OUT_OF_HOST_MEMORY)
    CLMARCH_STATUS(CL_PROFILING_INFO_NOT_AVAILABLE)
    CLMARCH_STATUS(CL_BUILD_PROGRAM_FAILURE)
    CLMARCH_STATUS(CL_INVALID_VALUE)
    CLMARCH_STATUS(CL_INVALID_DEVICE)
    CLMARCH_STATUS(CL_INVALID_CONTEXT)
    CLMARCH_STATUS(CL_INVALID_COMMAND_QUEUE)
    CLMARCH_STATUS(CL_INVALID_MEM_OBJECT)
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
    CLMARCH_STATUS(CL_INVALID_GLOBAL_WORK_SIZE)
    CLMARCH_STATUS(CL_INVALID_BUFFER_SIZE)
#undef CLMARCH_STATUS
    default:
      return fmt::format("OpenCL error {}", status);
  }
}

void throw_device_error(const DeviceEntry& device, const cl::Error& error) {
  std::string message =
      fmt::format("OpenCL error on {}: {} failed with {}", device.label(), error.what(), cl_status_name(error.err()));
  if (const auto* build = dynamic_cast<const cl::BuildError*>(&error)) {
    message += "; build log:";
    for (const auto& [log_device, log] : build->getBuildLog()) {
      message.append("\n").append(log);
    }
  }
  throw DeviceError(message);
}

}  // namespace clmarch
