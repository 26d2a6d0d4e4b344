// Membership and the wording of allowed intervals in error messages.
#include "scene/value_range.hpp"

#include <fmt/format.h>

#include <cmath>

namespace clmarch {
namespace {

/// A bound as people write it: integers in full (2147483647), others to 6 digits (3.40282e+38).
std::string readable_bound(double v) {
  return v == std::floor(v) && std::abs(v) < 1e15 ? fmt::format("{:.0f}", v) : fmt::format("{:.6g}", v);
}

}  // namespace

bool Range::contains(double v) const {
  const bool above = low_open ? v > low : v >= low;
  const bool below = high_open ? v < high : v <= high;
  return above && below;
}

std::string Range::describe() const {
  const bool bounded_low = std::isfinite(low);
  const bool bounded_high = std::isfinite(high);
  if (bounded_low && bounded_high) {
    return fmt::format("in {}{}, {}{}", low_open ? "(" : "[", readable_bound(low), readable_bound(high),
                       high_open ? ")" : "]");
  }
  if (bounded_low) return fmt::format("{} {}", low_open ? ">" : ">=", readable_bound(low));
  if (bounded_high) return fmt::format("{} {}", high_open ? "<" : "<=", readable_bound(high));
  return "a finite number";
}

}  // namespace clmarch
