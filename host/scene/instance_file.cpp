// CSV reading for instance files (and clmarch field's points): comma-separated, a header row, '#'
// comment lines, no quoting.
#include "scene/instance_file.hpp"

#include "common/cancellation.hpp"
#include "common/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string_view>

namespace clmarch {
namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

/// The fields of a line with the 1-based column each starts at.
std::vector<std::pair<std::string_view, int>> fields_of(std::string_view line) {
  std::vector<std::pair<std::string_view, int>> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    const std::string_view raw =
        line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    const std::size_t lead = std::min(raw.find_first_not_of(" \t"), raw.size());
    fields.emplace_back(trimmed(raw), static_cast<int>(start + lead + 1));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

}  // namespace

InstanceTable read_instance_table(const std::string& path, long long max_rows, const std::string& what) {
  const BlockingCall uninterruptible_read;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read the {}: {}", path, what, std::strerror(errno)));
  InstanceTable table;
  table.path = path;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string_view text = trimmed(line);
    if (text.empty() || text.front() == '#') continue;
    const auto fields = fields_of(text);
    if (table.columns.empty()) {
      for (const auto& [name, column] : fields) {
        if (name.empty())
          throw InputError(fmt::format("{}:{}:{}: the header row has an empty column name", path, number, column));
        if (std::find(table.columns.begin(), table.columns.end(), name) != table.columns.end()) {
          throw InputError(
              fmt::format("{}:{}:{}: column '{}' appears twice in the header row", path, number, column, name));
        }
        table.columns.emplace_back(name);
      }
      table.header_line = number;
      continue;
    }
    if (fields.size() != table.columns.size()) {
      throw InputError(fmt::format("{}:{}: the row has {} values (expected {}, one per column of the header: {})", path,
                                   number, fields.size(), table.columns.size(), fmt::join(table.columns, ",")));
    }
    if (static_cast<long long>(table.rows.size()) >= max_rows) {
      throw InputError(fmt::format("{}:{}: too many rows (expected at most {})", path, number, max_rows));
    }
    std::vector<double> values;
    values.reserve(fields.size());
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const auto [text_value, column] = fields[i];
      double value = 0.0;
      const auto [end, error] = std::from_chars(text_value.data(), text_value.data() + text_value.size(), value);
      if (error != std::errc() || end != text_value.data() + text_value.size() || !std::isfinite(value)) {
        throw InputError(fmt::format("{}:{}:{}: {} must be a finite number (got '{}')", path, number, column,
                                     table.columns[i], text_value));
      }
      values.push_back(value);
    }
    table.rows.push_back(std::move(values));
    table.lines.push_back(number);
    if (table.rows.size() % 65536 == 0) throw_if_cancelled();
  }
  if (in.bad()) throw InputError(fmt::format("{}: cannot read the {}: {}", path, what, std::strerror(errno)));
  if (table.columns.empty())
    throw InputError(fmt::format("{}: the {} is empty (it needs a header row of column names)", path, what));
  return table;
}

}  // namespace clmarch
