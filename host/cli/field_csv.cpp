// Points in, samples out, as CSV.
#include "cli/field_csv.hpp"

#include "common/errors.hpp"
#include "scene/instance_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <limits>

namespace clmarch {

std::vector<glm::dvec3> read_points_csv(const std::string& path) {
  const InstanceTable table = read_instance_table(path, std::numeric_limits<long long>::max(), "points file");
  if (table.columns != std::vector<std::string>{"x", "y", "z"}) {
    throw InputError(fmt::format("{}:{}: the header must be x,y,z (got {})", path, table.header_line,
                                 fmt::join(table.columns, ",")));
  }
  std::vector<glm::dvec3> points;
  points.reserve(table.rows.size());
  for (const std::vector<double>& row : table.rows) points.emplace_back(row[0], row[1], row[2]);
  return points;
}

std::string field_csv_text(const std::vector<glm::dvec3>& points, const FieldSamples& samples) {
  std::string text = "x,y,z,distance,r,g,b\n";
  auto out = std::back_inserter(text);
  for (std::size_t i = 0; i < points.size(); ++i) {
    // fmt's "{}" is the shortest text that reads back as the same float or double (at most 9 and
    // 17 significant digits), so no value changes on its way through the file.
    fmt::format_to(out, "{},{},{},", points[i].x, points[i].y, points[i].z);
    if (samples.distance_in_double) {
      fmt::format_to(out, "{},", samples.distance[i]);
    } else {
      fmt::format_to(out, "{},", static_cast<float>(samples.distance[i]));
    }
    fmt::format_to(out, "{},{},{}\n", samples.color[3 * i], samples.color[3 * i + 1], samples.color[3 * i + 2]);
  }
  return text;
}

}  // namespace clmarch
