// The CSV of `clmarch bench --sweep`: one row per combination, stable column names
// (docs/cli.md), read by scripts/sweep-plot.py.
#pragma once

#include "bench/sweep_run.hpp"

#include <string>
#include <vector>

namespace clmarch {

/// Column names, in order.
std::vector<std::string> sweep_csv_columns();

/// The header line and one line per row, each ending in a newline. scene labels every row.
std::string sweep_csv(const std::string& scene, const SweepResult& result, bool with_header);

/// Throws InputError unless path is missing or starts with this header (checked before a sweep
/// with --append renders anything).
void check_sweep_csv_appendable(const std::string& path);

/// Writes the CSV to path atomically. With append, the rows go after those already in the file,
/// whose header must be this one (else InputError); a missing file is created with the header.
void write_sweep_csv(const std::string& path, const std::string& scene, const SweepResult& result, bool append);

}  // namespace clmarch
