// The OpenCL renderer's dispatch: images split into chunks give the same buffers as one dispatch.
#include "render/opencl_renderer.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

namespace clmarch {
namespace {

TEST(OpenClRenderer, ChunkedDispatchEqualsOneDispatch) {
  Scene scene = testing::scene_from_yaml("sdf: {torus: {}}\nrender: {width: 67, height: 31}\n");
  for (int lanes : {1, 16}) {
    OpenClOptions whole, chunked;
    whole.lanes = chunked.lanes = lanes;
    chunked.max_chunk_pixels = 300;
    const RenderResult a = render_opencl(scene, whole);
    const RenderResult b = render_opencl(scene, chunked);
    EXPECT_EQ(a.stats.chunks, 1);
    EXPECT_GT(b.stats.chunks, 5);
    for (int c = 0; c < kChannelCount; ++c) {
      EXPECT_EQ(a.buffers.planes[c], b.buffers.planes[c]) << kChannelNames[c] << " lanes " << lanes;
    }
  }
}

}  // namespace
}  // namespace clmarch
