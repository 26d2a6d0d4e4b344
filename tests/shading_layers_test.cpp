// The shading's layers in the --buffers EXR (ao, diffuse, specular): the terms of each hit's lit
// color, so that without fog, mirrors, step-count darkening or tone mapping they sum to the color,
// also when anti-aliased over a black sky; fog scales them as it scales the surface's light.
#include "reference/reference_renderer.hpp"
#include "render/opencl_renderer.hpp"
#include "support/test_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace clmarch {
namespace {

using testing::scene_from_yaml;

/// Two lights (one point), soft shadows and normal occlusion over a floor, a sphere and a box, on
/// a black sky; model is the shading model's line.
std::string lit_scene(const std::string& model) {
  return fmt::format(
      "camera: {{position: [0, 1, 6], look_at: [0, 0, 0], fov: 50}}\n"
      "render: {{width: 48, height: 32}}\n"
      "sdf:\n  union:\n"
      "    - plane: {{normal: [0, 1, 0], offset: 1, color: [0.5, 0.5, 0.5]}}\n"
      "    - sphere: {{center: [-1.2, 0, 0], radius: 0.8, color: [0.9, 0.3, 0.2]}}\n"
      "    - box: {{center: [1.2, 0, 0], half_size: [0.6, 0.6, 0.6], color: [0.2, 0.5, 0.9], metallic: 0.6, roughness: "
      "0.3}}\n"
      "lights:\n"
      "  - directional: {{direction: [-1, 2, 1.5], color: [1, 1, 1], intensity: 0.8}}\n"
      "  - point: {{position: [2, 3, 2], color: [1, 0.9, 0.8], intensity: 2}}\n"
      "shading: {{{}, ambient: 0.2, background: [0, 0, 0], shadows: {{mode: soft, k: 16}}, ambient_occlusion: {{}}}}\n",
      model);
}

/// The program of a --buffers render, which writes the layers.
OpenClOptions buffers_program() {
  OpenClOptions options;
  options.purpose = KernelPurpose::Buffers;
  return options;
}

/// The sum of the three layers' channel c (0, 1, 2: r, g, b) at pixel (i, j), and of their sizes.
struct LayerSum {
  double sum = 0.0;
  double size = 0.0;
};
LayerSum layer_sum(const FrameBuffers& b, int c, int i, int j) {
  LayerSum s;
  for (int layer = 0; layer < 3; ++layer) {
    const double v = b.at(kLayerChannels[3 * layer + c], i, j);
    s.sum += v;
    s.size += std::abs(v);
  }
  return s;
}

/// Checks that every pixel's color is the sum of its layers: float sums on the device (two
/// roundings of the terms' size), each mean rounded once more when anti-aliased, a few units of
/// float's roundoff in all. Returns the specular layer's total.
double expect_layers_sum_to_the_color(const FrameBuffers& b, const std::string& what) {
  const double roundoff = 0x1p-24;
  double specular = 0.0;
  for (int j = 0; j < b.height; ++j) {
    for (int i = 0; i < b.width; ++i) {
      for (int c = 0; c < 3; ++c) {
        const LayerSum s = layer_sum(b, c, i, j);
        const double color = b.at(static_cast<Channel>(static_cast<int>(Channel::R) + c), i, j);
        EXPECT_NEAR(color, s.sum, 8.0 * roundoff * s.size + 1e-30)
            << what << " pixel " << i << "," << j << " channel " << c;
        specular += b.at(kLayerChannels[6 + c], i, j);
      }
      if (!std::isfinite(b.at(Channel::Depth, i, j)) && b.at(Channel::Samples, i, j) == 1.0f) {
        for (Channel layer : kLayerChannels) EXPECT_EQ(b.at(layer, i, j), 0.0f) << what << ": a miss has no layers";
      }
    }
  }
  return specular;
}

TEST(ShadingLayers, SumToTheColorOnBothBackendsAlsoAntiAliased) {
  for (const char* model : {"model: blinn_phong, specular: 0.6, shininess: 32", "model: pbr"}) {
    for (int samples : {1, 4}) {
      Scene scene = scene_from_yaml(lit_scene(model));
      scene.render.samples = samples;
      scene.render.adaptive = false;
      const std::string what = fmt::format("{}, {} samples", model, samples);
      for (int lanes : {1, 16}) {
        OpenClOptions options;
        options.lanes = lanes;
        options.purpose = KernelPurpose::Buffers;
        const FrameBuffers device = render_opencl(scene, options).buffers;
        EXPECT_GT(expect_layers_sum_to_the_color(device, what + fmt::format(", lanes {}", lanes)), 1.0)
            << what << ": highlights";
      }
      EXPECT_GT(expect_layers_sum_to_the_color(render_reference(scene), what + ", reference"), 1.0);
    }
  }
}

TEST(ShadingLayers, LambertHasNoSpecularLayer) {
  const Scene scene = scene_from_yaml(lit_scene("model: lambert"));
  const FrameBuffers device = render_opencl(scene, buffers_program()).buffers;
  double ao = 0.0, diffuse = 0.0;
  for (int j = 0; j < device.height; ++j) {
    for (int i = 0; i < device.width; ++i) {
      for (int c = 0; c < 3; ++c) {
        ao += device.at(kLayerChannels[c], i, j);
        diffuse += device.at(kLayerChannels[3 + c], i, j);
        EXPECT_EQ(device.at(kLayerChannels[6 + c], i, j), 0.0f);
      }
    }
  }
  EXPECT_GT(ao, 1.0);
  EXPECT_GT(diffuse, ao);
  EXPECT_EQ(expect_layers_sum_to_the_color(device, "lambert"), 0.0);
}

// Beer-Lambert fog leaves exp(-density t) of the surface's light: each layer of a fogged render is
// the unfogged one times that, within float's rounding of the two renders' terms and of the
// exponential (the same hits: fog changes no march).
TEST(ShadingLayers, FogScalesEachLayerByWhatItLeaves) {
  const double density = 0.15;
  const Scene clear = scene_from_yaml(lit_scene("model: blinn_phong, specular: 0.6"));
  Scene foggy = clear;
  foggy.shading.fog = Fog{glm::dvec3(0.7, 0.8, 0.9), density};
  for (const bool reference : {false, true}) {
    const FrameBuffers a = reference ? render_reference(clear) : render_opencl(clear, buffers_program()).buffers;
    const FrameBuffers b = reference ? render_reference(foggy) : render_opencl(foggy, buffers_program()).buffers;
    int hits = 0;
    for (int j = 0; j < a.height; ++j) {
      for (int i = 0; i < a.width; ++i) {
        const float depth = a.at(Channel::Depth, i, j);
        ASSERT_EQ(depth, b.at(Channel::Depth, i, j));
        if (!std::isfinite(depth)) continue;
        ++hits;
        const double left = std::exp(-density * depth);
        for (Channel layer : kLayerChannels) {
          const double clear_value = a.at(layer, i, j);
          EXPECT_NEAR(b.at(layer, i, j), clear_value * left, 64.0 * 0x1p-24 * (clear_value + 1.0))
              << (reference ? "reference" : "device") << " " << kChannelNames[static_cast<int>(layer)] << " at " << i
              << "," << j;
        }
        // The fog's own light is the rest of the color.
        const double fog_light = 0.7 * (1.0 - left);
        EXPECT_NEAR(b.at(Channel::R, i, j) - layer_sum(b, 0, i, j).sum, fog_light, 1e-5);
      }
    }
    EXPECT_GT(hits, 48 * 32 / 2);
  }
}

}  // namespace
}  // namespace clmarch
