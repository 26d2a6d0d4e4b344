// Sample points, the adaptive decision and the mean of the samples.
#include "frame/antialias.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace clmarch {
namespace {

/// The base-2 radical inverse of i: its bits mirrored about the binary point.
double radical_inverse_2(unsigned i) {
  double value = 0.0;
  double digit = 0.5;
  for (; i != 0; i >>= 1, digit *= 0.5) {
    if (i & 1u) value += digit;
  }
  return value;
}

double shifted(double x) { return x + 0.5 < 1.0 ? x + 0.5 : x - 0.5; }

/// A color channel as a viewer compares it: the square root of the linear value clamped to
/// [0, 1], close to its sRGB encoding (and a tenth of its cost, for every pixel of the image).
float perceived(float linear) { return std::sqrt(std::clamp(std::isnan(linear) ? 0.0f : linear, 0.0f, 1.0f)); }

/// The centre render's values the decision compares, per pixel.
struct EdgeInputs {
  const std::vector<float>& depth;
  std::vector<float> seen[3];
};

/// Whether pixels a and b (row-major indices) differ by an edge.
bool is_edge(const EdgeInputs& in, std::size_t a, std::size_t b, const EdgeThresholds& t) {
  const bool hit_a = std::isfinite(in.depth[a]), hit_b = std::isfinite(in.depth[b]);
  if (hit_a != hit_b) return true;
  if (hit_a) {
    const double near = std::min(in.depth[a], in.depth[b]), far = std::max(in.depth[a], in.depth[b]);
    if (far > t.depth_ratio * near) return true;
  }
  for (const std::vector<float>& channel : in.seen) {
    if (std::abs(channel[a] - channel[b]) > t.color_difference) return true;
  }
  return false;
}

}  // namespace

glm::dvec2 sample_point(int index, int count) {
  return {shifted(static_cast<double>(index) / count), shifted(radical_inverse_2(static_cast<unsigned>(index)))};
}

std::vector<std::uint8_t> pixels_to_refine(const FrameBuffers& centre, bool adaptive,
                                           const EdgeThresholds& thresholds) {
  const int width = centre.width, height = centre.height;
  std::vector<std::uint8_t> refine(static_cast<std::size_t>(width) * height, adaptive ? 0 : 1);
  if (!adaptive) return refine;
  // Each edge between two neighbours flags both: the right and lower neighbours of every pixel
  // cover each pair once. A straight edge crossing a pixel leaves the neighbour along its normal's
  // larger axis on its other side, so the diagonals would find no pixel it crosses that these miss.
  EdgeInputs inputs{centre.plane(Channel::Depth), {}};
  const Channel colors[3] = {Channel::R, Channel::G, Channel::B};
  for (int c = 0; c < 3; ++c) {
    inputs.seen[c].resize(refine.size());
    std::transform(centre.plane(colors[c]).begin(), centre.plane(colors[c]).end(), inputs.seen[c].begin(), perceived);
  }
  const int di[2] = {1, 0}, dj[2] = {0, 1};
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const std::size_t a = static_cast<std::size_t>(j) * width + i;
      for (int k = 0; k < 2; ++k) {
        const int ni = i + di[k], nj = j + dj[k];
        if (ni < 0 || ni >= width || nj >= height) continue;
        const std::size_t b = static_cast<std::size_t>(nj) * width + ni;
        if (is_edge(inputs, a, b, thresholds)) refine[a] = refine[b] = 1;
      }
    }
  }
  return refine;
}

SampleSums::SampleSums(const FrameBuffers& centre, std::vector<std::uint8_t> refine, bool with_layers)
    : refine_(std::move(refine)), averaged_{Channel::R, Channel::G, Channel::B, Channel::A} {
  if (with_layers) averaged_.insert(averaged_.end(), std::begin(kLayerChannels), std::end(kLayerChannels));
  sums_.assign(averaged_.size() * refine_.size(), 0.0);
  const std::vector<float>& depth = centre.plane(Channel::Depth);
  std::vector<float> values(averaged_.size());
  for (std::size_t i = 0; i < refine_.size(); ++i) {
    if (!refine_[i]) continue;
    for (std::size_t k = 0; k < averaged_.size(); ++k) {
      values[k] = averaged_[k] == Channel::A ? (std::isfinite(depth[i]) ? 1.0f : 0.0f) : centre.plane(averaged_[k])[i];
    }
    add(i, values.data());
  }
}

void SampleSums::finish(FrameBuffers& buffers, int count) const {
  set_single_sample_coverage(buffers);
  const double scale = 1.0 / count;
  for (std::size_t i = 0; i < refine_.size(); ++i) {
    if (!refine_[i]) continue;
    for (std::size_t k = 0; k < averaged_.size(); ++k) {
      buffers.plane(averaged_[k])[i] = static_cast<float>(sums_[averaged_.size() * i + k] * scale);
    }
    buffers.plane(Channel::Samples)[i] = static_cast<float>(count);
  }
}

void set_single_sample_coverage(FrameBuffers& buffers) {
  const std::vector<float>& depth = buffers.plane(Channel::Depth);
  for (std::size_t i = 0; i < depth.size(); ++i) {
    buffers.plane(Channel::A)[i] = std::isfinite(depth[i]) ? 1.0f : 0.0f;
    buffers.plane(Channel::Samples)[i] = 1.0f;
  }
}

}  // namespace clmarch
