// `--frames A:B --fps F`: which frames an animation renders, at which times, to which files.
#pragma once

#include <string>
#include <vector>

namespace clmarch {

/// Frames first..last (both included), frame n at time n / fps seconds.
struct FrameRange {
  int first = 0;
  int last = 0;
  double fps = 24.0;

  int count() const { return last - first + 1; }
  double time_of(int frame) const { return frame / fps; }
};

/// Up to most frames of the range, ascending: all of them, or the first two, the last and the
/// others spread evenly between (what an animation changes shows in a few of its frames).
std::vector<int> sample_frames(const FrameRange& range, int most);

/// Parses "A:B" (0 <= A <= B <= 999999) with the fps; throws InputError naming --frames or --fps.
FrameRange parse_frame_range(const std::string& frames, double fps);

/// The file of one frame. A run of '#' in the file name is replaced by the frame number padded
/// with zeros to the run's length ("shot_####.png" -> "shot_0012.png"); without one, "_NNNN" is
/// inserted before the extension, padded to 4 digits or to the digits of the last frame.
std::string frame_path(const std::string& pattern, int frame, const FrameRange& range);

}  // namespace clmarch
