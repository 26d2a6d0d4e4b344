// The pattern forms of a node's color key.
#include "scene/color_pattern_reader.hpp"

#include "scene/expression.hpp"

#include <fmt/format.h>

#include <regex>

namespace clmarch {
namespace {

constexpr const char* kAxisNames[] = {"x", "y", "z"};
/// The variables of a color expression: the point in the node's frame, and the time.
const std::vector<std::string> kPointVariables = {"x", "y", "z", "t"};

/// Whether a color component names the point: then the color is a pattern of it.
bool names_the_point(const YAML::Node& component) {
  static const std::regex point(R"((^|[^A-Za-z0-9_])[xyz]([^A-Za-z0-9_(]|$))");
  return component.IsScalar() && std::regex_search(component.Scalar(), point);
}

/// colors: [a, b] of a pattern (its default where absent).
void read_pair(const YamlReader& yaml, const YAML::Node& params, const std::string& what, ColorPattern& pattern) {
  const YAML::Node colors = params["colors"];
  if (!colors) return;
  if (!colors.IsSequence() || colors.size() != 2) {
    yaml.fail(colors, fmt::format("{}.colors must be a list of 2 colors [a, b] (got {}){}", what,
                                  colors.IsSequence() ? fmt::format("{} items", colors.size()) : describe_yaml(colors),
                                  glsl_vector_hint(colors, "colors")));
  }
  for (std::size_t i = 0; i < 2; ++i) pattern.colors[i] = yaml.color(colors[i], fmt::format("{}.colors[{}]", what, i));
}

ColorPattern read_cells(const YamlReader& yaml, const std::string& kind, const YAML::Node& params,
                        const std::string& what) {
  ColorPattern pattern;
  if (kind == "checker") {
    pattern.kind = ColorPattern::Kind::Checker;
    yaml.expect_map(params, what, {"size", "colors"});
  } else if (kind == "stripes") {
    pattern.kind = ColorPattern::Kind::Stripes;
    yaml.expect_map(params, what, {"size", "colors", "axis"});
    if (const YAML::Node axis = params["axis"]) pattern.axis = yaml.choice(axis, what + ".axis", kAxisNames);
  } else {
    pattern.kind = ColorPattern::Kind::Grid;
    pattern.colors[0] = glm::dvec3(0.8);
    pattern.colors[1] = glm::dvec3(0.1);
    yaml.expect_map(params, what, {"size", "colors", "line_width", "axes"});
    if (const YAML::Node axes = params["axes"]) {
      if (!axes.IsSequence() || axes.size() == 0 || axes.size() > 3) {
        yaml.fail(axes, fmt::format("{}.axes must be a list of 1 to 3 axes, e.g. [x, z] (got {})", what,
                                    describe_yaml(axes)));
      }
      for (bool& on : pattern.grid_axes) on = false;
      for (std::size_t i = 0; i < axes.size(); ++i)
        pattern.grid_axes[yaml.choice(axes[i], fmt::format("{}.axes[{}]", what, i), kAxisNames)] = true;
    }
  }
  yaml.optional_number(params, "size", what + ".size", pattern.size, Range::positive());
  read_pair(yaml, params, what, pattern);
  if (pattern.kind == ColorPattern::Kind::Grid) {
    pattern.line_width = 0.05 * pattern.size;
    yaml.optional_number(params, "line_width", what + ".line_width", pattern.line_width,
                         Range{0.0, pattern.size, true, true});
  }
  return pattern;
}

ColorPattern read_expressions(const YamlReader& yaml, const YAML::Node& value, const std::string& what) {
  ColorPattern pattern;
  pattern.kind = ColorPattern::Kind::Expression;
  pattern.time = yaml.time();
  for (std::size_t i = 0; i < 3; ++i) {
    const YAML::Node component = value[i];
    const std::string where = fmt::format("{}[{}]", what, i);
    if (!component.IsScalar())
      yaml.fail(component, fmt::format("{} must be a number or an expression of x, y, z and t (got {})", where,
                                       describe_yaml(component)));
    pattern.expressions[i] = component.Scalar();
    try {
      // The tree first: its message offers only what a color expression takes, where muparser's
      // would offer all of its own functions.
      parse_expression_tree(pattern.expressions[i], kPointVariables);
      evaluate_expression(pattern.expressions[i], {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}, {"t", yaml.time()}});
    } catch (const ExpressionError& e) {
      yaml.fail(component, fmt::format("{} must be an expression of the point x, y, z and the time t (got '{}': {})",
                                       where, pattern.expressions[i], e.what()));
    }
  }
  return pattern;
}

}  // namespace

void read_node_color(const YamlReader& yaml, const YAML::Node& value, const std::string& what, Node& node) {
  if (value.IsMap()) {
    yaml.expect_map(value, what, {"checker", "stripes", "grid"});
    if (value.size() != 1) yaml.fail(value, what + " must have exactly one key: checker, stripes or grid");
    const auto entry = value.begin();
    const std::string kind = entry->first.Scalar();
    node.color_pattern = read_cells(yaml, kind, entry->second, what + "." + kind);
    return;
  }
  if (value.IsSequence() && value.size() == 3 &&
      (names_the_point(value[0]) || names_the_point(value[1]) || names_the_point(value[2]))) {
    node.color_pattern = read_expressions(yaml, value, what);
    return;
  }
  node.color = yaml.color(value, what);
}

}  // namespace clmarch
