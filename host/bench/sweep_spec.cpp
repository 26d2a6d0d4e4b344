// Sweep axes: parsing, the Cartesian product and the kernel keys.
#include "bench/sweep_spec.hpp"

#include "common/errors.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <iterator>
#include <set>

namespace clmarch {
namespace {

constexpr const char* kSyntax = "expected KEY=V1,V2,... e.g. render.epsilon=1e-3,1e-4";

/// Splits at commas outside brackets, so YAML lists and maps stay whole.
std::vector<std::string> split_values(const std::string& text) {
  std::vector<std::string> values(1);
  int depth = 0;
  for (char c : text) {
    if (c == '[' || c == '{') ++depth;
    if (c == ']' || c == '}') --depth;
    if (c == ',' && depth == 0) {
      values.emplace_back();
    } else {
      values.back() += c;
    }
  }
  return values;
}

template <std::size_t N>
int index_of(const std::string& value, const char* const (&names)[N]) {
  const auto found = std::find(std::begin(names), std::end(names), value);
  return found == std::end(names) ? -1 : static_cast<int>(found - std::begin(names));
}

void check_kernel_value(const std::string& key, const std::string& value) {
  const auto fail = [&](const std::string& expected) {
    throw InputError(fmt::format("--sweep {}={}: '{}' is not a value of {} (expected one of: {})", key, value, value,
                                 key, expected));
  };
  if (key == "lanes" && value != "1" && value != "4" && value != "8" && value != "16") fail("1, 4, 8, 16");
  if (key == "precision" && index_of(value, kPrecisionNames) < 0)
    fail(fmt::format("{}", fmt::join(kPrecisionNames, ", ")));
  if ((key == "fast_math" || key == "native_math") && index_of(value, kSwitchNames) < 0) {
    fail(fmt::format("{}", fmt::join(kSwitchNames, ", ")));
  }
}

}  // namespace

bool is_kernel_key(const std::string& key) {
  return std::find(std::begin(kSweepKernelKeys), std::end(kSweepKernelKeys), key) != std::end(kSweepKernelKeys);
}

SweepAxis parse_sweep_axis(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) throw InputError(fmt::format("--sweep {}: {}", text, kSyntax));
  SweepAxis axis;
  axis.key = text.substr(0, equals);
  if (axis.key.find('.') == std::string::npos && !is_kernel_key(axis.key)) {
    throw InputError(
        fmt::format("--sweep {}: unknown key '{}' (expected a scene key path such as render.epsilon, or one of: {})",
                    text, axis.key, fmt::join(kSweepKernelKeys, ", ")));
  }
  if (axis.key == "render.width" || axis.key == "render.height") {
    throw InputError(
        fmt::format("--sweep {}: the image size is --size's, one for the whole sweep (every row is compared "
                    "pixel by pixel with a reference of that size)",
                    axis.key));
  }
  axis.values = split_values(text.substr(equals + 1));
  for (std::size_t i = 0; i < axis.values.size(); ++i) {
    const std::string& value = axis.values[i];
    if (value.empty()) throw InputError(fmt::format("--sweep {}: empty value ({})", text, kSyntax));
    if (std::find(axis.values.begin(), axis.values.begin() + static_cast<std::ptrdiff_t>(i), value) !=
        axis.values.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw InputError(fmt::format("--sweep {}: the value '{}' is given twice", text, value));
    }
    if (is_kernel_key(axis.key)) check_kernel_value(axis.key, value);
  }
  return axis;
}

std::vector<SweepCombination> expand_sweep(const std::vector<SweepAxis>& axes) {
  std::set<std::string> keys;
  std::size_t count = 1;
  for (const SweepAxis& axis : axes) {
    if (!keys.insert(axis.key).second) throw InputError(fmt::format("--sweep {}: the key is swept twice", axis.key));
    count *= axis.values.size();
    if (count > kMaxSweepCombinations) {
      throw InputError(fmt::format("--sweep: more than {} combinations; sweep fewer values", kMaxSweepCombinations));
    }
  }
  std::vector<SweepCombination> out(1);
  for (const SweepAxis& axis : axes) {
    std::vector<SweepCombination> next;
    for (const SweepCombination& prefix : out) {
      for (const std::string& value : axis.values) {
        next.push_back(prefix);
        next.back().emplace_back(axis.key, value);
      }
    }
    out = std::move(next);
  }
  return out;
}

std::vector<SweepCombination> expand_one_at_a_time(const std::vector<SweepAxis>& axes) {
  std::set<std::string> keys;
  std::vector<SweepCombination> out(1);
  for (const SweepAxis& axis : axes) {
    if (!keys.insert(axis.key).second) throw InputError(fmt::format("--sweep {}: the key is swept twice", axis.key));
    for (const std::string& value : axis.values) out.push_back({{axis.key, value}});
  }
  if (out.size() > kMaxSweepCombinations) {
    throw InputError(fmt::format("--sweep: more than {} combinations; sweep fewer values", kMaxSweepCombinations));
  }
  return out;
}

std::vector<std::string> scene_sets(const SweepCombination& combination) {
  std::vector<std::string> sets;
  for (const auto& [key, value] : combination) {
    if (!is_kernel_key(key)) sets.push_back(fmt::format("{}={}", key, value));
  }
  return sets;
}

std::vector<std::string> picture_sets(const SweepCombination& combination) {
  std::vector<std::string> sets = scene_sets(combination);
  std::erase_if(sets, [](const std::string& set) { return set.rfind("render.", 0) == 0; });
  return sets;
}

OpenClOptions with_kernel_settings(OpenClOptions options, const SweepCombination& combination) {
  for (const auto& [key, value] : combination) {
    if (key == "lanes") options.lanes = std::stoi(value);
    if (key == "precision") options.variant.precision = static_cast<Precision>(index_of(value, kPrecisionNames));
    if (key == "fast_math") options.variant.fast_math = value == "on";
    if (key == "native_math") options.variant.native_math = value == "on";
  }
  if (options.variant.native_math && options.variant.precision == Precision::Double) {
    throw InputError(
        fmt::format("--sweep: native_math=on needs precision=float (OpenCL has no native_* functions for "
                    "double); sweep them in separate runs ({})",
                    combination_label(combination)));
  }
  return options;
}

std::string combination_label(const SweepCombination& combination) {
  std::vector<std::string> parts;
  for (const auto& [key, value] : combination) parts.push_back(fmt::format("{}={}", key, value));
  return fmt::format("{}", fmt::join(parts, " "));
}

}  // namespace clmarch
