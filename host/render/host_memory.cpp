// Host memory estimates and the memory left to this process (Linux: /proc, cgroups, rlimits).
#include "render/host_memory.hpp"

#include "frame/frame_buffers.hpp"

#include <fmt/format.h>

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <vector>

namespace clmarch {
namespace {

/// Channels of the --buffers EXR (image_writer.cpp), which the writer interleaves into one copy.
constexpr std::uint64_t kWrittenChannels = 14;

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

/// Room under RLIMIT_AS (ulimit -v): the limit less the address space in use (VmSize).
std::optional<std::uint64_t> address_space_room() {
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
  // Checked before OpenCL starts: the driver's own reservation is still to come.
  const std::uint64_t cap = static_cast<std::uint64_t>(limit.rlim_cur);
  const std::uint64_t taken = used + kOpenClDriverAddressSpace;
  return taken < cap ? cap - taken : 0;
}

std::string gibibytes(std::uint64_t bytes) { return fmt::format("{:.1f} GiB", static_cast<double>(bytes) / (1024.0 * 1024.0 * 1024.0)); }

}  // namespace

std::uint64_t host_bytes_per_pixel(int samples) {
  const std::uint64_t frame = 2 * kChannelCount * sizeof(float) + 3 * kWrittenChannels * sizeof(float);
  // SampleSums' four doubles, its flags and the device's copy of them, four read-back planes.
  const std::uint64_t antialiasing = 4 * sizeof(double) + 2 + 4 * sizeof(float);
  return samples > 1 ? frame + antialiasing : frame;
}

std::uint64_t render_host_bytes(int width, int height, int samples) {
  return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) * host_bytes_per_pixel(samples);
}

std::optional<AvailableMemory> available_host_memory() {
  std::optional<AvailableMemory> best;
  const auto consider = [&](std::optional<std::uint64_t> bytes, const char* source) {
    if (bytes && (!best || *bytes < best->bytes)) best = AvailableMemory{*bytes, source};
  };
  std::optional<std::uint64_t> physical = meminfo_available();
  const char* physical_source = "MemAvailable in /proc/meminfo";
  if (!physical) {
    const long pages = sysconf(_SC_AVPHYS_PAGES);
    const long page_size = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page_size > 0) physical = static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
    physical_source = "free physical memory";
  }
  consider(physical, physical_source);
  consider(cgroup_room(), "room under the cgroup's memory limit");
  consider(address_space_room(), "room under the address-space limit, ulimit -v");
  return best;
}

std::string host_memory_shortfall(int width, int height, const AvailableMemory& available, int samples) {
  const std::uint64_t needed = render_host_bytes(width, height, samples);
  if (needed <= available.bytes) return {};
  return fmt::format("{} x {} pixels need {} bytes ({}) of host memory ({} bytes per pixel), but only {} bytes ({}) "
                     "are available ({})",
                     width, height, needed, gibibytes(needed), host_bytes_per_pixel(samples), available.bytes,
                     gibibytes(available.bytes), available.source);
}

}  // namespace clmarch
