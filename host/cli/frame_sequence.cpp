// Frame ranges and numbered file names.
#include "cli/frame_sequence.hpp"

#include "common/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>

namespace clmarch {

FrameRange parse_frame_range(const std::string& frames, double fps) {
  static const std::regex pattern(R"(^(\d{1,6}):(\d{1,6})$)");
  std::smatch match;
  if (!std::regex_match(frames, match, pattern)) {
    throw InputError(fmt::format("--frames {}: expected FIRST:LAST frame numbers, e.g. 0:47", frames));
  }
  FrameRange range;
  range.first = std::stoi(match[1].str());
  range.last = std::stoi(match[2].str());
  if (range.last < range.first) {
    throw InputError(fmt::format("--frames {}: the last frame must not come before the first", frames));
  }
  if (!std::isfinite(fps) || fps <= 0.0 || fps > 1000.0) {
    throw InputError(fmt::format("--fps {}: expected frames per second in (0, 1000]", fps));
  }
  range.fps = fps;
  return range;
}

std::vector<int> sample_frames(const FrameRange& range, int most) {
  const int count = range.count();
  std::vector<int> frames;
  if (count <= most) {
    for (int frame = range.first; frame <= range.last; ++frame) frames.push_back(frame);
    return frames;
  }
  frames = {range.first, range.first + 1};
  // most - 2 more, evenly from the third frame to the last.
  const int spread = most - 2;
  for (int i = 1; i <= spread; ++i) {
    frames.push_back(range.first + 1 + static_cast<int>(static_cast<long long>(count - 2) * i / spread));
  }
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

std::string frame_path(const std::string& pattern, int frame, const FrameRange& range) {
  const std::filesystem::path path(pattern);
  std::string name = path.filename().string();
  const std::size_t hashes = name.find('#');
  if (hashes != std::string::npos) {
    const std::size_t width = name.find_first_not_of('#', hashes) == std::string::npos
                                  ? name.size() - hashes
                                  : name.find_first_not_of('#', hashes) - hashes;
    name.replace(hashes, width, fmt::format("{:0{}d}", frame, width));
  } else {
    const int width = std::max<int>(4, static_cast<int>(fmt::format("{}", range.last).size()));
    name = fmt::format("{}_{:0{}d}{}", path.stem().string(), frame, width, path.extension().string());
  }
  return (path.parent_path() / name).string();
}

}  // namespace clmarch
