// Sweep rows as CSV (RFC 4180 quoting for the few text fields that may need it).
#include "bench/sweep_csv.hpp"

#include "common/atomic_file.hpp"
#include "common/errors.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace clmarch {
namespace {

const char* const kColumns[] = {
    "scene", "width", "height", "device", "combination", "defaults",
    // settings in force
    "lanes", "precision", "fast_math", "native_math", "epsilon", "hit_threshold", "cone_factor", "max_steps",
    "over_relaxation", "normal_method", "normal_epsilon",
    // speed
    "kernel_ms", "kernel_ms_min", "kernel_ms_max", "steps_per_pixel",
    // error against the reference
    "both_hit", "depth_rms", "depth_p99", "depth_max", "depth_rel_rms", "depth_rel_p99", "depth_rel_max",
    "mask_silhouette_rate", "mask_interior_rate", "normal_p99_deg", "color_psnr_db",
    // the reference
    "reference_epsilon", "reference_max_steps",
    // anti-aliasing in force, and the reference's rays a pixel (columns added after the others)
    "samples", "adaptive", "reference_samples"};

std::string quoted(const std::string& field) {
  if (field.find_first_of(",\"\n") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// 7 significant digits, more than any figure here is worth ("inf" for an infinite PSNR).
std::string number(double value) { return fmt::format("{:.7g}", value); }

std::string row_line(const std::string& scene, const SweepResult& result, const SweepRow& row) {
  const RenderSettings& r = row.render;
  const CheckReport& e = row.error;
  const double pixels = std::max(e.pixels, 1);
  const auto [min_ms, max_ms] = std::minmax_element(row.kernel_ms_runs.begin(), row.kernel_ms_runs.end());
  const bool timed = !row.kernel_ms_runs.empty();
  const std::vector<std::string> fields = {quoted(scene),
                                           std::to_string(r.width),
                                           std::to_string(r.height),
                                           quoted(row.device),
                                           quoted(combination_label(row.combination)),
                                           row.is_defaults ? "1" : "0",
                                           std::to_string(row.lanes),
                                           kPrecisionNames[static_cast<int>(row.variant.precision)],
                                           row.variant.fast_math ? "on" : "off",
                                           row.variant.native_math ? "on" : "off",
                                           number(r.epsilon),
                                           kHitThresholdNames[static_cast<int>(r.hit_threshold)],
                                           number(r.cone_factor),
                                           std::to_string(r.max_steps),
                                           r.over_relaxation ? number(*r.over_relaxation) : "auto",
                                           kNormalMethodNames[static_cast<int>(r.normal_method)],
                                           number(r.normal_epsilon),
                                           number(row.kernel_ms),
                                           number(timed ? *min_ms : 0.0),
                                           number(timed ? *max_ms : 0.0),
                                           number(row.steps_per_pixel),
                                           std::to_string(e.both_hit),
                                           number(e.depth_abs.rms),
                                           number(e.depth_abs.p99),
                                           number(e.depth_abs.max),
                                           number(e.depth_rel.rms),
                                           number(e.depth_rel.p99),
                                           number(e.depth_rel.max),
                                           number(e.mask_mismatch_silhouette / pixels),
                                           number(e.mask_mismatch_interior / pixels),
                                           number(e.normal_angle_p99),
                                           number(e.color_psnr_db),
                                           number(row.reference_epsilon),
                                           std::to_string(result.reference_max_steps),
                                           std::to_string(r.samples),
                                           r.adaptive ? "true" : "false",
                                           std::to_string(row.reference_samples)};
  return fmt::format("{}\n", fmt::join(fields, ","));
}

std::string header_line() { return fmt::format("{}\n", fmt::join(kColumns, ",")); }

}  // namespace

std::vector<std::string> sweep_csv_columns() { return {std::begin(kColumns), std::end(kColumns)}; }

std::string sweep_csv(const std::string& scene, const SweepResult& result, bool with_header) {
  std::string out = with_header ? header_line() : std::string();
  for (const SweepRow& row : result.rows) out += row_line(scene, result, row);
  return out;
}

namespace {

/// The file's text, "" when it does not exist or is empty; InputError when its header is not the sweep's.
std::string existing_rows(const std::string& path) {
  if (!std::filesystem::exists(path)) return {};
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  std::string existing = text.str();
  if (!existing.empty() && existing.compare(0, header_line().size(), header_line()) != 0) {
    throw InputError(
        fmt::format("--csv {}: cannot append, its header is not the sweep's (columns: docs/cli.md)", path));
  }
  return existing;
}

}  // namespace

void check_sweep_csv_appendable(const std::string& path) { existing_rows(path); }

void write_sweep_csv(const std::string& path, const std::string& scene, const SweepResult& result, bool append) {
  const std::string existing = append ? existing_rows(path) : std::string();
  write_file_atomically(path, existing + sweep_csv(scene, result, existing.empty()));
}

}  // namespace clmarch
