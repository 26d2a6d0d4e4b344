// The memory left to this process: /proc/meminfo, the cgroup's limit and RLIMIT_AS.
#include "common/available_memory.hpp"

#include <fmt/format.h>

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <vector>

namespace clmarch {
namespace {

/// "MemAvailable:  22800696 kB" from /proc/meminfo, in bytes.
std::optional<std::uint64_t> meminfo_available() {
  std::ifstream in("/proc/meminfo");
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string key;
    std::uint64_t kib = 0;
    if (fields >> key >> kib && key == "MemAvailable:") return kib * 1024;
  }
  return std::nullopt;
}

std::optional<std::uint64_t> read_number(const std::string& path) {
  std::ifstream in(path);
  std::uint64_t value = 0;
  if (in >> value) return value;  // "max" (cgroup v2: no limit) reads as nothing
  return std::nullopt;
}

/// Room under a cgroup memory limit: v2 (memory.max) or v1 (memory.limit_in_bytes), looked up
/// under the process's own cgroup path first and then at the mount's root (inside a container the
/// root is the container's cgroup).
std::optional<std::uint64_t> cgroup_room() {
  std::vector<std::pair<std::string, std::string>> candidates;  // {limit file, usage file}
  std::ifstream in("/proc/self/cgroup");
  for (std::string line; std::getline(in, line);) {
    const std::size_t first = line.find(':');
    const std::size_t second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const std::string path = line.substr(second + 1);
    if (controllers.empty()) {
      candidates.emplace_back("/sys/fs/cgroup" + path + "/memory.max", "/sys/fs/cgroup" + path + "/memory.current");
    } else if (controllers == "memory") {
      candidates.emplace_back("/sys/fs/cgroup/memory" + path + "/memory.limit_in_bytes",
                              "/sys/fs/cgroup/memory" + path + "/memory.usage_in_bytes");
    }
  }
  candidates.emplace_back("/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current");
  candidates.emplace_back("/sys/fs/cgroup/memory/memory.limit_in_bytes", "/sys/fs/cgroup/memory/memory.usage_in_bytes");
  // cgroup v1 writes "no limit" as a huge number (9223372036854771712).
  constexpr std::uint64_t kNoLimit = std::uint64_t{1} << 60;
  for (const auto& [limit_file, usage_file] : candidates) {
    const std::optional<std::uint64_t> limit = read_number(limit_file);
    if (!limit || *limit >= kNoLimit) continue;
    const std::uint64_t used = read_number(usage_file).value_or(0);
    return used < *limit ? *limit - used : 0;
  }
  return std::nullopt;
}

/// Room under RLIMIT_AS (ulimit -v): the limit less the address space in use (VmSize) and the
/// driver's reservation still to come.
std::optional<std::uint64_t> address_space_room(std::uint64_t driver_still_to_reserve) {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  std::ifstream in("/proc/self/status");
  std::uint64_t used = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string key;
    std::uint64_t kib = 0;
    if (fields >> key >> kib && key == "VmSize:") used = kib * 1024;
  }
  const std::uint64_t cap = static_cast<std::uint64_t>(limit.rlim_cur);
  const std::uint64_t taken = used + driver_still_to_reserve;
  return taken < cap ? cap - taken : 0;
}

}  // namespace

std::optional<AvailableMemory> available_host_memory(std::uint64_t driver_still_to_reserve) {
  std::optional<AvailableMemory> best;
  const auto consider = [&](std::optional<std::uint64_t> bytes, const char* source) {
    if (bytes && (!best || *bytes < best->bytes)) best = AvailableMemory{*bytes, source};
  };
  std::optional<std::uint64_t> physical = meminfo_available();
  const char* physical_source = "MemAvailable in /proc/meminfo";
  if (!physical) {
    const long pages = sysconf(_SC_AVPHYS_PAGES);
    const long page_size = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page_size > 0)
      physical = static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
    physical_source = "free physical memory";
  }
  consider(physical, physical_source);
  consider(cgroup_room(), "room under the cgroup's memory limit");
  consider(address_space_room(driver_still_to_reserve), "room under the address-space limit, ulimit -v");
  return best;
}

std::string bytes_and_gibibytes(std::uint64_t bytes) {
  return fmt::format("{} bytes ({:.1f} GiB)", bytes, static_cast<double>(bytes) / (1024.0 * 1024.0 * 1024.0));
}

std::string memory_shortfall(std::uint64_t needed, const AvailableMemory& available) {
  if (needed <= available.bytes) return {};
  return fmt::format("but only {} are available ({})", bytes_and_gibibytes(available.bytes), available.source);
}

}  // namespace clmarch
