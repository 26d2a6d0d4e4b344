// Host memory estimates of a render.
#include "render/host_memory.hpp"

#include "frame/frame_buffers.hpp"

#include <fmt/format.h>

namespace clmarch {
namespace {

/// Channels of the --buffers EXR (image_writer.cpp), which the writer interleaves into one copy.
constexpr std::uint64_t kWrittenChannels = 26;

}  // namespace

std::uint64_t host_bytes_per_pixel(int samples) {
  const std::uint64_t frame =
      2 * static_cast<std::uint64_t>(kChannelCount) * sizeof(float) + 3 * kWrittenChannels * sizeof(float);
  // SampleSums' doubles (color, hits and the layers) and its flag (the refining pass's buffers are
  // of a fixed size).
  const std::uint64_t antialiasing = 13 * sizeof(double) + 1;
  return samples > 1 ? frame + antialiasing : frame;
}

std::uint64_t render_host_bytes(int width, int height, int samples) {
  return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) * host_bytes_per_pixel(samples);
}

std::string host_memory_shortfall(int width, int height, const AvailableMemory& available, int samples) {
  const std::uint64_t needed = render_host_bytes(width, height, samples);
  const std::string shortfall = memory_shortfall(needed, available);
  if (shortfall.empty()) return {};
  return fmt::format("{} x {} pixels need {} of host memory ({} bytes per pixel), {}", width, height,
                     bytes_and_gibibytes(needed), host_bytes_per_pixel(samples), shortfall);
}

}  // namespace clmarch
