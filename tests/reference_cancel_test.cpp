// The CPU reference polls cancellation (Ctrl-C) before each row: once it is requested, a render
// throws Cancelled instead of finishing (tests/interrupt_test.cpp checks the same through signals).
#include "common/cancellation.hpp"
#include "reference/reference_renderer.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

namespace clmarch {
namespace {

/// Requests cancellation for the test's duration and withdraws it however the test ends.
struct CancellationRequested {
  CancellationRequested() { cancellation_requested().store(true); }
  ~CancellationRequested() { cancellation_requested().store(false); }
};

TEST(ReferenceCancellation, RequestedCancellationStopsTheRender) {
  Scene scene = testing::scene_from_yaml("sdf: {sphere: {}}\nrender: {width: 8, height: 4}\n");
  {
    const CancellationRequested cancel;
    EXPECT_THROW(render_reference(scene), Cancelled);
  }
  // Without the request the same render completes.
  EXPECT_NO_THROW(render_reference(scene));
}

}  // namespace
}  // namespace clmarch
