// The memory this process may still use (Linux: /proc, cgroups, rlimits), so that work too large
// for the machine fails with a message naming what is too big before it is allocated (rather than
// in the OOM killer).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace clmarch {

/// Address space the OpenCL driver takes for itself, which the room under ulimit -v must leave it:
/// PoCL 3.1 here, a 16x16 render's VmPeak is 876 MB with OpenCL and 431 MB on the reference.
inline constexpr std::uint64_t kOpenClDriverAddressSpace = std::uint64_t{512} << 20;
/// The part of it still to come once the platform is loaded (select_device): the context and the
/// program's build. PoCL 3.1 here, 2026-11-25: VmSize 798 MB after select_device, VmPeak 863 MB for
/// a 16x16 render of a sphere; 1,306 and 1,383 MB for 100,000 spheres (their grid included).
inline constexpr std::uint64_t kOpenClBuildAddressSpace = std::uint64_t{128} << 20;

/// Memory this process may still use, and where the figure came from.
struct AvailableMemory {
  std::uint64_t bytes = 0;
  /// "MemAvailable in /proc/meminfo", "the cgroup's memory.max", ...
  std::string source;
};

/// The smallest of: MemAvailable (/proc/meminfo; free physical pages where that is missing), the
/// room left under the cgroup's memory limit, and the room left under RLIMIT_AS less the address
/// space the OpenCL driver will still reserve. Nothing when none of them can be read.
std::optional<AvailableMemory> available_host_memory(std::uint64_t driver_still_to_reserve = kOpenClDriverAddressSpace);

/// "N bytes (G GiB)".
std::string bytes_and_gibibytes(std::uint64_t bytes);

/// Empty when needed bytes fit in available; else "but only A bytes (G GiB) are available (source)".
std::string memory_shortfall(std::uint64_t needed, const AvailableMemory& available);

}  // namespace clmarch
