// Host memory a render needs, so that an image too large for the machine fails with a message
// before anything is allocated (rather than in the OOM killer).
#pragma once

#include "common/available_memory.hpp"

#include <cstdint>
#include <string>

namespace clmarch {

/// Host bytes per pixel at a render's peak: the frame buffers (every channel of FrameBuffers in
/// float), the OpenCL output buffer (as many planes; host memory on a CPU device), and the image
/// writer's interleaved copy of the eight --buffers channels, OpenImageIO's conversion of that
/// copy and the encoded file in memory (each at most as large as the copy); with samples > 1 also
/// the anti-aliasing's sums, refine flags and read-back planes (host/frame/antialias.hpp).
std::uint64_t host_bytes_per_pixel(int samples = 1);

/// Host bytes a render of width x height needs at its peak: host_bytes_per_pixel(samples) per pixel.
std::uint64_t render_host_bytes(int width, int height, int samples = 1);

/// Empty when a width x height render fits in available; else the reason, one line without the
/// leading "what: ": "W x H pixels need N bytes (G GiB) of host memory (B bytes per pixel), but only A bytes ...".
std::string host_memory_shortfall(int width, int height, const AvailableMemory& available, int samples = 1);

}  // namespace clmarch
