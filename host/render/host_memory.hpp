// Host memory a render needs and the memory the machine has left, so that an image too large for
// the machine fails with a message before anything is allocated (rather than in the OOM killer).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace clmarch {

/// Host bytes per pixel at a render's peak: the frame buffers (every channel of FrameBuffers in
/// float) plus the image writer's interleaved copy of the eight --buffers channels and
/// OpenImageIO's conversion of that copy (at most as large again).
std::uint64_t host_bytes_per_pixel();

/// Host bytes a render of width x height needs at its peak: host_bytes_per_pixel() per pixel.
std::uint64_t render_host_bytes(int width, int height);

/// Memory this process may still use, and where the figure came from.
struct AvailableMemory {
  std::uint64_t bytes = 0;
  /// "MemAvailable in /proc/meminfo", "the cgroup's memory.max", ...
  std::string source;
};

/// The smallest of: MemAvailable (/proc/meminfo; free physical pages where that is missing), the
/// room left under the cgroup's memory limit, and the room left under RLIMIT_AS. Nothing when
/// none of them can be read.
std::optional<AvailableMemory> available_host_memory();

/// Empty when a width x height render fits in available; else the reason, one line without the
/// leading "what: ": "W x H pixels need N bytes (G GiB) of host memory (B bytes per pixel), but only A bytes ...".
std::string host_memory_shortfall(int width, int height, const AvailableMemory& available);

}  // namespace clmarch
