// Inputs the scene fuzzer (fuzz/scene_fuzzer.cpp) found to break the loader or the code
// generator, one file each in tests/fuzz_regressions/: each must now be refused with a message.
#include "common/errors.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

namespace clmarch {
namespace {

TEST(FuzzRegressions, EveryFoundInputIsRefusedWithAMessage) {
  int inputs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testing::source_path("tests/fuzz_regressions"))) {
    ++inputs;
    const std::string path = entry.path().string();
    try {
      load_scene_file(path);
      ADD_FAILURE() << path << " was accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find(path + ":"), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  EXPECT_GT(inputs, 0) << "tests/fuzz_regressions/ is empty";
}

}  // namespace
}  // namespace clmarch
