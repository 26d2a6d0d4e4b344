// OpenCL platforms and devices: listing them and picking the one a render runs on.
#pragma once

#include <CL/opencl.hpp>

#include <optional>
#include <string>
#include <vector>

namespace clmarch {

/// One device, numbered in the order `clmarch devices` prints.
struct DeviceEntry {
  int index = 0;
  cl::Platform platform;
  cl::Device device;
  std::string platform_name;
  std::string name;
  bool is_gpu = false;
  bool is_cpu = false;
  /// Whether the platform is PoCL (its kernel cache and compiler behaviour are known).
  bool is_pocl() const;
  /// Whether the device has cl_khr_fp64 (double programs: render.precision: double).
  bool has_fp64() const;

  /// "NAME (PLATFORM)", for messages and --stats.
  std::string label() const;
};

/// Every device of every platform; empty when no platform exists.
std::vector<DeviceEntry> list_devices();

/// The device with this index, or by default the first GPU, else the first CPU, else the first
/// device. Throws InputError for an unknown index and DeviceError when there is no device.
DeviceEntry select_device(std::optional<int> index);

/// The DeviceError message when there is no device: what was called and what to install.
std::string no_device_message();

/// Pixels per work-item that suit the device: explicit vector packets on CPUs (PoCL does not
/// vectorise the per-pixel march loop), one pixel per work-item on GPUs.
int default_lanes(const DeviceEntry& device);

/// Whether the kernels may let the compiler fuse a * b + c where the source does not (OpenCL's
/// FP_CONTRACT). Only where the fused operations are known to be the same at every packet width:
/// PoCL's. NVIDIA's compiler fuses scalar and vector code differently (1 and 16 lanes an epsilon
/// of depth apart); forbidding it on PoCL would cost up to 10 % (docs/performance.md).
bool allows_fp_contraction(const DeviceEntry& device);

/// Work-items per work-group: GPUs want many; PoCL loops over the items of a group on one core, and
/// one fixed size keeps its per-size compile of the work-group function cached.
std::size_t default_local_size(const DeviceEntry& device);

/// For timings: asks PoCL to pin its worker threads to cores (POCL_AFFINITY=1) unless the
/// environment already sets POCL_AFFINITY. Call before the first OpenCL call of the process.
/// Unpinned, about half the processes on the 2-vCPU test machine ran the torus's ceiling kernel
/// 1.7x slower for their whole life, while the march kernels kept their times
/// (docs/performance.md); other OpenCL platforms ignore the variable.
void pin_pocl_threads_for_timing();

}  // namespace clmarch
