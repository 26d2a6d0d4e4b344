// Allowed intervals of scene numbers: shared by the kind declarations and the YAML reader.
#pragma once

#include <limits>
#include <string>

namespace clmarch {

/// The largest magnitude of a number in a scene: the largest float, as the device computes in float.
inline constexpr double kMaxSceneNumber = static_cast<double>(std::numeric_limits<float>::max());

/// An allowed interval for a number; open or closed at each end.
struct Range {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  bool low_open = false;
  bool high_open = false;

  static constexpr Range any() { return {}; }
  static constexpr Range positive() { return greater_than(0.0); }
  static constexpr Range greater_than(double lo) { return {lo, std::numeric_limits<double>::infinity(), true, false}; }
  static constexpr Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static constexpr Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static constexpr Range open(double lo, double hi) { return {lo, hi, true, true}; }
  /// (lo, hi]
  static constexpr Range left_open(double lo, double hi) { return {lo, hi, true, false}; }
  bool contains(double v) const;
  /// "> 0", "in [1, 65536]"
  std::string describe() const;
};

}  // namespace clmarch
