// Anti-aliasing shared by both renderers: where a pixel's samples lie, which pixels get more than
// their centre ray (the adaptive decision), and how the samples make the pixel's color and coverage.
#pragma once

#include "frame/frame_buffers.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace clmarch {

/// Sample index of count (0 <= index < count) as a point of the pixel, each coordinate in [0, 1)
/// from its top-left corner: the Hammersley set (index / count, radical inverse of index in base
/// 2), shifted by (0.5, 0.5) modulo 1 so that sample 0 is the centre, (0.5, 0.5). The shift keeps
/// the set's stratification: every column and every row of count strata holds one point.
glm::dvec2 sample_point(int index, int count);

/// Thresholds of the adaptive decision, each a jump between a pixel and one of its 4 neighbours
/// that marks an edge (docs/scene-format.md, "Anti-aliasing", says why these values). Normals are
/// not compared: programs that draw the color image alone do not write them, and the image must
/// not change with --buffers; a crease that shows in the image shows in the color test.
struct EdgeThresholds {
  /// The larger over the smaller depth of two hits.
  double depth_ratio = 1.1;
  /// Largest difference of a channel of the colors, each as its square root (about the sRGB
  /// encoding the image is seen in).
  double color_difference = 1.0 / 16.0;
};

/// One byte per pixel of centre (row-major), 1 where the pixel gets all its samples: with adaptive,
/// a pixel that differs from one of its 4 neighbours (within centre) by a hit against a miss or
/// a jump over a threshold; without, every pixel.
std::vector<std::uint8_t> pixels_to_refine(const FrameBuffers& centre, bool adaptive,
                                           const EdgeThresholds& thresholds = {});

/// Sums of the samples of the refined pixels, which finish turns into their means.
class SampleSums {
 public:
  /// with_layers: the shading's layers (kLayerChannels) are averaged with the color.
  SampleSums(const FrameBuffers& centre, std::vector<std::uint8_t> refine, bool with_layers);
  /// How many values a sample adds: r, g, b and its hit (1 or 0), then with the layers those of
  /// kLayerChannels in their order.
  std::size_t values_per_sample() const { return averaged_.size(); }
  /// Adds samples of pixel (row-major index) i: values_per_sample() values, each the sum over them.
  void add(std::size_t i, const float* values) {
    for (std::size_t k = 0; k < averaged_.size(); ++k) sums_[averaged_.size() * i + k] += values[k];
  }
  const std::vector<std::uint8_t>& refine() const { return refine_; }
  /// Writes into buffers (the centre render) R, G, B, A and the layers as the means of count
  /// samples of each refined pixel, the centre's included, and Samples; other pixels keep the
  /// centre's values, get A = 1 on a hit and 0 on a miss, and Samples = 1.
  void finish(FrameBuffers& buffers, int count) const;

 private:
  std::vector<std::uint8_t> refine_;
  /// The channels whose means are taken, in the order of add's values; A's is the hits'.
  std::vector<Channel> averaged_;
  /// Their sums per pixel; 0 for pixels not refined.
  std::vector<double> sums_;
};

/// A and Samples of a render of one ray per pixel: A = 1 on a hit, 0 on a miss; Samples = 1.
void set_single_sample_coverage(FrameBuffers& buffers);

}  // namespace clmarch
