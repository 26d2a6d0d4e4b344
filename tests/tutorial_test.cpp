// docs/tutorial.md cannot rot silently: every step's scene (docs/tutorial/step_N.yaml) loads and
// renders, every YAML snippet the page shows is a verbatim part of the step file it names, and
// every file the page's commands and images refer to exists.
#include "render/opencl_renderer.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <sstream>

namespace clmarch {
namespace {

using testing::read_text;
using testing::source_path;

std::vector<std::string> tutorial_steps() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(source_path("docs/tutorial"))) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

class TutorialStep : public ::testing::TestWithParam<std::string> {};

TEST_P(TutorialStep, LoadsAndRenders) {
  Scene scene = load_scene_file(source_path("docs/tutorial/" + GetParam()).string());
  scene.render.width = 48;
  scene.render.height = 27;
  const FrameBuffers buffers = render_opencl(scene, OpenClOptions{}).buffers;
  int hits = 0;
  for (std::size_t i = 0; i < buffers.plane(Channel::Depth).size(); ++i) {
    for (Channel c : {Channel::R, Channel::G, Channel::B}) ASSERT_TRUE(std::isfinite(buffers.plane(c)[i])) << i;
    hits += std::isfinite(buffers.plane(Channel::Depth)[i]) ? 1 : 0;
  }
  EXPECT_GT(hits, 48 * 27 / 2) << "the floor and the shapes fill most of the image";
}

INSTANTIATE_TEST_SUITE_P(Tutorial, TutorialStep, ::testing::ValuesIn(tutorial_steps()),
                         [](const auto& info) { return info.param.substr(0, info.param.find('.')); });

TEST(Tutorial, SnippetsAreVerbatimPartsOfTheirStepFiles) {
  std::istringstream page(read_text(source_path("docs/tutorial.md")));
  // A snippet: a line ```yaml, a line "# docs/tutorial/step_N.yaml ...", the lines shown, ```.
  int snippets = 0;
  for (std::string line; std::getline(page, line);) {
    if (line != "```yaml") continue;
    std::string first;
    std::getline(page, first);
    ASSERT_TRUE(first.starts_with("# docs/tutorial/step_")) << "a YAML snippet must name its step file: " << first;
    const std::string name = first.substr(2, first.find(".yaml") + 5 - 2);
    std::string shown;
    for (std::string body; std::getline(page, body) && body != "```";) shown += body + "\n";
    ++snippets;
    const std::string file = read_text(source_path(name));
    ASSERT_FALSE(file.empty()) << name << " is missing";
    EXPECT_NE(file.find(shown), std::string::npos)
        << "docs/tutorial.md shows lines that " << name << " does not hold:\n"
        << shown;
  }
  EXPECT_GE(snippets, static_cast<int>(tutorial_steps().size())) << "every step shows its YAML";
}

TEST(Tutorial, ReferencedFilesExist) {
  const std::string page = read_text(source_path("docs/tutorial.md"));
  const std::regex reference(R"((docs/tutorial/step_\d+\.yaml|images/tutorial_\w+\.png))");
  int references = 0;
  for (auto it = std::sregex_iterator(page.begin(), page.end(), reference); it != std::sregex_iterator(); ++it) {
    ++references;
    const std::string name = (*it)[1].str();
    const std::string path = name.starts_with("images/") ? "docs/" + name : name;
    EXPECT_TRUE(std::filesystem::exists(source_path(path))) << path;
  }
  EXPECT_GE(references, 2 * static_cast<int>(tutorial_steps().size()));
}

TEST(Tutorial, TheBuffersItListsAreTheOnesWritten) {
  testing::TempDir dir;
  const std::filesystem::path exr = dir / "step_7.exr";
  const auto result = testing::run_clmarch({"render", source_path("docs/tutorial/step_7.yaml").string(), "--size",
                                            "16x9", "--no-image", "--buffers", exr.string()});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto input = OIIO::ImageInput::open(exr.string());
  ASSERT_TRUE(input);
  const OIIO::ImageSpec& spec = input->spec();
  const std::string page = read_text(source_path("docs/tutorial.md"));
  EXPECT_NE(page.find(fmt::format("{} channel, float openexr", spec.nchannels)), std::string::npos)
      << "docs/tutorial.md section 8 must give the EXR's " << spec.nchannels << " channels";
  EXPECT_NE(page.find(fmt::format("channel list: {}\n", fmt::join(spec.channelnames, ", "))), std::string::npos)
      << "docs/tutorial.md section 8 must list: " << fmt::format("{}", fmt::join(spec.channelnames, ", "));
}

}  // namespace
}  // namespace clmarch
