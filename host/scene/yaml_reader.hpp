// Typed, validated reads from a YAML document, each failure an InputError that names the file,
// line and column of the offending value.
#pragma once

#include "scene/value_range.hpp"

#include <yaml-cpp/yaml.h>

#include <glm/glm.hpp>

#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace clmarch {

class YamlReader {
 public:
  /// time is the value of t in expressions (animation).
  YamlReader(std::string source_name, double time) : source_(std::move(source_name)), time_(time) {}

  /// The value of t in expressions.
  double time() const { return time_; }
  /// Whether a number read so far is an expression whose value depends on t (an animation).
  bool read_time() const { return read_time_; }
  /// Notes a read of the time other than through a number (user code that reads iTime).
  void note_time_read() const { read_time_ = true; }
  /// The document the nodes come from; lets where() place an empty value at its key.
  void set_document(const YAML::Node& root) { document_ = root; }
  /// "file:line:col" of a node, or "file (--set)" for values that came from an override.
  std::string where(const YAML::Node& node) const;
  /// Throws InputError "where: message"; a long message keeps its start and end (it may quote a
  /// huge value), while listing, appended after it, is never cut (the names a value may take).
  [[noreturn]] void fail(const YAML::Node& at, const std::string& message, std::string_view listing = {}) const;

  /// Fails unless node is a map whose keys are all in allowed and none repeats.
  void expect_map(const YAML::Node& node, const std::string& what,
                  std::initializer_list<std::string_view> allowed) const;
  void expect_map(const YAML::Node& node, const std::string& what, const std::vector<std::string_view>& allowed) const;

  /// A number, or an expression of the time t such as "cos(t)" or "0.5 + 0.2 * sin(2 * pi * t)"
  /// (muparser syntax), evaluated at the scene's time.
  double number(const YAML::Node& node, const std::string& what, Range range = Range::any()) const;
  int integer(const YAML::Node& node, const std::string& what, Range range) const;
  std::string text(const YAML::Node& node, const std::string& what) const;
  /// true or false, spelt so (not yes/no/on/off, which YAML 1.1 also reads as booleans).
  bool boolean(const YAML::Node& node, const std::string& what) const;
  glm::dvec3 vec3(const YAML::Node& node, const std::string& what, Range range = Range::any()) const;
  /// Above this a color's channel is more likely 0..255 than linear light: a warning says so.
  static constexpr double kPlausibleColor = 10.0;
  /// A color: [r, g, b] or one number for gray; components >= 0; a word (red) fails saying so. A
  /// channel past kPlausibleColor warns unless told not to (emitted light may be that bright).
  glm::dvec3 color(const YAML::Node& node, const std::string& what, bool warn_past_plausible = true) const;
  /// Index of node's text in names, else fails listing them.
  template <std::size_t N>
  int choice(const YAML::Node& node, const std::string& what, const char* const (&names)[N]) const {
    return choice_of(node, what, names, N);
  }
  int choice(const YAML::Node& node, const std::string& what, std::span<const char* const> names) const {
    return choice_of(node, what, names.data(), names.size());
  }

  /// Reads map[key] into out if present (the default stays otherwise).
  void optional_number(const YAML::Node& map, const char* key, const std::string& what, double& out,
                       Range range = Range::any()) const;
  void optional_vec3(const YAML::Node& map, const char* key, const std::string& what, glm::dvec3& out,
                     Range range = Range::any()) const;
  /// map[key], failing if it is absent.
  YAML::Node required(const YAML::Node& map, const char* key, const std::string& what) const;

 private:
  int choice_of(const YAML::Node& node, const std::string& what, const char* const* names, std::size_t count) const;
  YAML::Mark mark_of(const YAML::Node& node) const;
  std::string source_;
  double time_;
  mutable bool read_time_ = false;
  std::optional<YAML::Node> document_;
};

/// How a YAML value looks in a message: its text for scalars, else "a list" or "a map".
std::string describe_yaml(const YAML::Node& node);

/// How to write value, read for key, as a YAML list when it is GLSL's vector constructor (text
/// such as "vec3(1, .5, 0)") or the pieces of one or more that a flow list split at their commas:
/// "; YAML reads GLSL's vec3(1, .5, 0) as text: write a list, color: [1, 0.5, 0]". Else empty.
std::string glsl_vector_hint(const YAML::Node& value, std::string_view key);

/// Parses text without building nodes and throws InputError at the first node past max_nodes
/// (scalars, nulls, lists, maps; an alias counts once here), so that a huge file costs no more
/// than scanning that many nodes, or at the start of a second document ('---'). Malformed YAML
/// throws YAML::ParserException.
void check_yaml_node_count(const std::string& text, const std::string& source_name, long long max_nodes);

}  // namespace clmarch
