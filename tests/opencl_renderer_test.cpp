// The OpenCL renderer's dispatch: images split into chunks give the same buffers as one dispatch.
#include "render/opencl_renderer.hpp"

#include "codegen/kernel_source.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace clmarch {
namespace {

// Also with the coarse cone pass, whose starts each chunk's packets read by the image row, not
// the row within the chunk: the chunked image is the one dispatch's, bit for bit.
TEST(OpenClRenderer, ChunkedDispatchEqualsOneDispatch) {
  for (const char* yaml : {"sdf: {torus: {}}\nrender: {width: 67, height: 31}\n",
                           "sdf: {torus: {}}\nrender: {width: 67, height: 41, coarse_pass: cone}\n"}) {
    const Scene scene = testing::scene_from_yaml(yaml);
    for (int lanes : {1, 16}) {
      OpenClOptions whole, chunked;
      whole.lanes = chunked.lanes = lanes;
      chunked.max_chunk_pixels = 300;
      const RenderResult a = render_opencl(scene, whole);
      const RenderResult b = render_opencl(scene, chunked);
      EXPECT_EQ(a.stats.chunks, 1);
      EXPECT_GT(b.stats.chunks, 5);
      for (int c = 0; c < kChannelCount; ++c) {
        EXPECT_EQ(a.buffers.planes[c], b.buffers.planes[c]) << kChannelNames[c] << " lanes " << lanes << "\n" << yaml;
      }
    }
  }
}

// A band of rows (a tile of an MPI render) is exactly those rows of the whole image, with the
// coarse pass (run once, at the first band) and at every packet width; bands in any order, the
// last one short, and a chunk limit that splits a band too.
TEST(OpenClRenderer, BandsOfRowsEqualTheWholeImage) {
  for (const char* yaml : {"sdf: {torus: {}}\nrender: {width: 67, height: 45}\n",
                           "sdf: {torus: {}}\nrender: {width: 67, height: 45, coarse_pass: cone}\n"}) {
    const Scene scene = testing::scene_from_yaml(yaml);
    for (int lanes : {1, 4, 8, 16}) {
      OpenClOptions options;
      options.lanes = lanes;
      const RenderResult whole = render_opencl(scene, options);
      for (std::size_t max_chunk : {std::size_t{0}, std::size_t{600}}) {
        options.max_chunk_pixels = max_chunk;
        OpenClRenderer renderer(scene, options);
        for (const auto& [first, rows] : {std::pair{16, 24}, std::pair{0, 8}, std::pair{40, 5}, std::pair{8, 8}}) {
          const RenderResult band = renderer.render_rows(first, rows);
          ASSERT_EQ(band.buffers.height, rows);
          for (int c = 0; c < kChannelCount; ++c) {
            const auto from = whole.buffers.planes[c].begin() + first * scene.render.width;
            const std::vector<float> expected(from, from + rows * scene.render.width);
            EXPECT_EQ(band.buffers.planes[c], expected)
                << kChannelNames[c] << " rows " << first << " + " << rows << ", lanes " << lanes << "\n"
                << yaml;
          }
        }
      }
    }
  }
}

TEST(OpenClRenderer, BandsStartOnlyAtTheAlignment) {
  const Scene scene = testing::scene_from_yaml("sdf: {torus: {}}\nrender: {width: 16, height: 16}\n");
  OpenClRenderer renderer(scene, OpenClOptions{});
  EXPECT_THROW(renderer.render_rows(4, 8), std::logic_error);
  EXPECT_THROW(renderer.render_rows(8, 9), std::logic_error) << "past the last row";
}

// A color image alone (Color) writes what the full shaded program writes but the normal planes,
// which stay 0; the program still computes normals for the shading. A scene with a reflection
// and occlusion, so that every use of the normal shows in the color.
TEST(OpenClRenderer, ColorProgramEqualsTheShadedOneWithoutNormalPlanes) {
  const Scene scene = testing::scene_from_yaml(
      "sdf:\n  union:\n    - torus: {color: [0.9, 0.3, 0.2], reflectivity: 0.5}\n    - plane: {normal: [0, 1, 0], "
      "offset: -0.5}\n"
      "render: {width: 61, height: 37}\nlights:\n  - point: {position: [2, 3, 1]}\n"
      "shading: {model: blinn_phong, step_ao: 200, reflections: 1, ambient_occlusion: {}, shadows: {mode: soft}}\n");
  OpenClOptions shaded, color;
  shaded.purpose = KernelPurpose::Shaded;
  color.purpose = KernelPurpose::Color;
  const FrameBuffers a = render_opencl(scene, shaded).buffers;
  const FrameBuffers b = render_opencl(scene, color).buffers;
  for (Channel c : {Channel::R, Channel::G, Channel::B, Channel::Depth, Channel::Steps}) {
    EXPECT_EQ(a.plane(c), b.plane(c)) << kChannelNames[static_cast<int>(c)];
  }
  const auto zero = [](const std::vector<float>& plane) {
    return std::all_of(plane.begin(), plane.end(), [](float v) { return v == 0.0f; });
  };
  for (Channel c : {Channel::NX, Channel::NY, Channel::NZ}) EXPECT_TRUE(zero(b.plane(c)));
  EXPECT_FALSE(zero(a.plane(Channel::NY)));
  EXPECT_EQ(generate_kernel_source(scene, {KernelPurpose::Color, 16}).find("#define WRITE_NORMALS"), std::string::npos);
  EXPECT_NE(generate_kernel_source(scene, {KernelPurpose::Shaded, 16}).find("#define WRITE_NORMALS"),
            std::string::npos);
  // The id and the layers are the --buffers program's alone: the shaded kernel that bench times
  // writes no more planes than it did before them.
  for (const char* define : {"#define WRITE_IDS", "#define WRITE_LAYERS"}) {
    EXPECT_EQ(generate_kernel_source(scene, {KernelPurpose::Shaded, 16}).find(define), std::string::npos) << define;
    EXPECT_NE(generate_kernel_source(scene, {KernelPurpose::Buffers, 16}).find(define), std::string::npos) << define;
  }
}

TEST(OpenClRenderer, CpuWorkItemsMarchPairsOfPacketsExceptUnderTheCellsTiling) {
  const Scene plain = testing::scene_from_yaml("sdf: {torus: {}}\n");
  const Scene cells =
      testing::scene_from_yaml("tiling: {cell: [1, 1, 1], method: cells}\nsdf: {sphere: {radius: 0.3}}\n");
  EXPECT_EQ(packets_per_item(plain, 16), 2);
  EXPECT_EQ(packets_per_item(plain, 4), 2);
  EXPECT_EQ(packets_per_item(plain, 1), 1);
  EXPECT_EQ(packets_per_item(cells, 16), 1);
  EXPECT_NE(generate_kernel_source(plain, {KernelPurpose::Shaded, 16}).find("#define PACKETS_PER_ITEM 2\n"),
            std::string::npos);
  EXPECT_NE(generate_kernel_source(cells, {KernelPurpose::Shaded, 16}).find("#define PACKETS_PER_ITEM 1\n"),
            std::string::npos);
}

TEST(OpenClRenderer, AnOddPacketAtTheEndOfARowOfWorkItemsIsMarchedAlone) {
  // 20 x 7 pixels in 4 x 4 tiles: 5 tiles a row, two rows of tiles (the second cut by the image),
  // so the pairs straddle rows and the last work-item holds one packet. Every pixel must match
  // one pixel per work-item (lanes 1), which marches the same rays alone.
  const Scene scene = testing::scene_from_yaml(
      "camera: {position: [0, 2, 2.5], look_at: [0, 0, 0]}\nsdf: {torus: {minor_radius: 0.5}}\nrender: {width: 20, "
      "height: 7}\n");
  OpenClOptions single, packets;
  single.lanes = 1;
  packets.lanes = 16;
  const RenderResult a = render_opencl(scene, single);
  const RenderResult b = render_opencl(scene, packets);
  EXPECT_EQ(a.buffers.plane(Channel::Steps), b.buffers.plane(Channel::Steps));
  int hits = 0;
  for (std::size_t i = 0; i < a.buffers.plane(Channel::Depth).size(); ++i) {
    const float da = a.buffers.plane(Channel::Depth)[i], db = b.buffers.plane(Channel::Depth)[i];
    ASSERT_EQ(std::isinf(da), std::isinf(db)) << "pixel " << i;
    if (std::isinf(da)) continue;
    ++hits;
    EXPECT_NEAR(da, db, 1e-5) << "pixel " << i;  // float rounding of the same steps
  }
  EXPECT_GT(hits, 20);
}

}  // namespace
}  // namespace clmarch
