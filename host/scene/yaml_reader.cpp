// Typed reads with line/column errors.
#include "scene/yaml_reader.hpp"

#include "common/errors.hpp"
#include "common/log.hpp"
#include "common/nearest_name.hpp"
#include "scene/expression.hpp"
#include "scene/glsl_vectors.hpp"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <set>
#include <sstream>

namespace clmarch {

std::string describe_yaml(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return "'" + node.Scalar() + "'";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a map";
    default:
      return "nothing";
  }
}

namespace {

/// The key a value's path ends with: "sdf.sphere.color" gives "color".
std::string_view key_of(std::string_view what) { return what.substr(what.rfind('.') + 1); }

/// The hint for text, GLSL's vectors as written (split: in pieces YAML cut at the commas);
/// several lists are one list of them.
std::string glsl_vector_hint_for(const std::string& text, bool split, std::string_view key) {
  std::string list = glsl_vectors_as_yaml(text);
  if (list.empty()) return {};
  if (!list.starts_with('[') || list.find(']') + 1 != list.size()) list = "[" + list + "]";
  return fmt::format("; YAML {} GLSL's {}{}: write a list, {}: {}", split ? "splits" : "reads", text,
                     split ? " at its commas" : " as text", key, list);
}

/// Where a flow map split GLSL's vector constructor at its commas into keys (`{color: vec3(1, .5,
/// 0)}` reads as color: "vec3(1", then keys ".5" and "0)"), how to write it; else empty.
std::string split_glsl_vector_hint(const YAML::Node& map) {
  std::string key, text;
  for (const auto& entry : map) {
    if (text.empty()) {
      if (entry.second.IsScalar() && starts_glsl_vector(entry.second.Scalar()) &&
          entry.second.Scalar().find(')') == std::string::npos) {
        key = entry.first.Scalar();
        text = entry.second.Scalar();
      }
    } else if (entry.second.IsNull()) {
      text += ", " + entry.first.Scalar();
      if (entry.first.Scalar().find(')') != std::string::npos) break;
    } else {
      break;
    }
  }
  // Pieces are short: a long text is some other mistake, and the hint would quote all of it.
  constexpr std::size_t kLongestVector = 200;
  return text.size() > kLongestVector ? std::string() : glsl_vector_hint_for(text, true, key);
}

}  // namespace

std::string glsl_vector_hint(const YAML::Node& value, std::string_view key) {
  if (value.IsScalar()) return glsl_vector_hint_for(value.Scalar(), false, key);
  if (!value.IsSequence()) return {};
  std::string text;
  for (const YAML::Node& item : value) {
    if (!item.IsScalar()) return {};
    text += (text.empty() ? "" : ", ") + item.Scalar();
  }
  return glsl_vector_hint_for(text, true, key);
}

namespace {

/// Counts parser events; the parse stops with an InputError at the first node past the limit.
class NodeCounter : public YAML::EventHandler {
 public:
  NodeCounter(const std::string& source_name, long long max_nodes) : source_(source_name), max_(max_nodes) {}
  void OnDocumentStart(const YAML::Mark& mark) override {
    if (documents_++ == 0) return;
    throw InputError(
        fmt::format("{}:{}:{}: a scene file holds one YAML document (got a second one after '---' here, "
                    "expected at most 1)",
                    source_, mark.line + 1, mark.column + 1));
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { count(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { count(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override {
    count(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    count(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    count(mark);
  }
  void OnMapEnd() override {}

 private:
  void count(const YAML::Mark& mark) {
    if (++count_ <= max_) return;
    throw InputError(fmt::format("{}:{}:{}: the file has too many YAML values (got value {} here, expected at most {})",
                                 source_, mark.line + 1, mark.column + 1, count_, max_));
  }
  const std::string& source_;
  long long max_;
  long long count_ = 0;
  int documents_ = 0;
};

/// Where YAML split an expression at its comma (a flow map reads `radius: max(0.1, t)` as the
/// value "max(0.1" and a key "t)"), how to keep it whole; else empty. Such pieces are short: a
/// long text with unbalanced parentheses is another mistake.
std::string split_expression_hint(const std::string& text) {
  constexpr std::size_t kLongestPiece = 200;
  if (text.size() > kLongestPiece ||
      std::count(text.begin(), text.end(), '(') == std::count(text.begin(), text.end(), ')'))
    return {};
  return "; an expression with a comma must be quoted, as in radius: \"max(0.1, t)\", or YAML splits it at the comma";
}

}  // namespace

void check_yaml_node_count(const std::string& text, const std::string& source_name, long long max_nodes) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  NodeCounter counter(source_name, max_nodes);
  // YAML::Load reads the first document only; a second one would be ignored without this.
  while (parser.HandleNextDocument(counter)) {
  }
}

YAML::Mark YamlReader::mark_of(const YAML::Node& node) const {
  // yaml-cpp marks an empty value (`camera:` at the end of its line) where the next token starts,
  // often on the next line and under another key: the key the value belongs to is the place.
  // A value from --set has no mark at all, and keeps it.
  if (!node.IsNull() || node.Mark().is_null() || !document_) return node.Mark();
  // Aliases can make the tree a graph with cycles: breadth first, so that a cycle does not hide the
  // rest of the document, and no further than any document's size.
  constexpr std::size_t kMostVisited = 1'000'000;
  std::deque<YAML::Node> pending = {*document_};
  for (std::size_t visited = 0; !pending.empty() && visited < kMostVisited; ++visited) {
    const YAML::Node at = pending.front();
    pending.pop_front();
    if (at.IsMap()) {
      for (const auto& entry : at) {
        if (entry.second.is(node)) return entry.first.Mark();
        pending.push_back(entry.second);
      }
    } else if (at.IsSequence()) {
      for (const YAML::Node& item : at) {
        // An empty item of a block list (a lone `-`) has no key: the list's start is the place, and
        // the message names the item's index. In a flow list (`[1, , 2]`) the next token is the
        // comma right after the empty item, which is as good.
        if (item.is(node) && at.Style() == YAML::EmitterStyle::Block) return at.Mark();
        pending.push_back(item);
      }
    }
  }
  return node.Mark();
}

std::string YamlReader::where(const YAML::Node& node) const {
  const YAML::Mark mark = mark_of(node);
  if (mark.is_null()) return source_ + " (--set)";
  return fmt::format("{}:{}:{}", source_, mark.line + 1, mark.column + 1);
}

void YamlReader::fail(const YAML::Node& at, const std::string& message, std::string_view listing) const {
  // A message quoting a huge value (a 100 KB expression) keeps its start, which says what is wrong,
  // and its end, which says why.
  constexpr std::size_t kHead = 400, kTail = 200;
  std::string shown = message;
  if (shown.size() > kHead + kTail + 100) {
    shown = fmt::format("{} [... {} characters ...] {}", message.substr(0, kHead), message.size() - kHead - kTail,
                        message.substr(message.size() - kTail));
  }
  throw InputError(fmt::format("{}: {}{}", where(at), shown, listing));
}

void YamlReader::expect_map(const YAML::Node& node, const std::string& what,
                            std::initializer_list<std::string_view> allowed) const {
  expect_map(node, what, std::vector<std::string_view>(allowed));
}

void YamlReader::expect_map(const YAML::Node& node, const std::string& what,
                            const std::vector<std::string_view>& allowed) const {
  if (!node.IsMap()) fail(node, fmt::format("{} must be a map (got {})", what, describe_yaml(node)));
  std::set<std::string> seen;
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    bool known = false;
    for (std::string_view a : allowed) known = known || a == key;
    if (!known) {
      // A split vector says more than a split expression: ".5" of vec3(1, .5, 0) is no expression.
      std::string hint = split_glsl_vector_hint(node);
      if (hint.empty()) hint = split_expression_hint(key);
      fail(entry.first, fmt::format("unknown key '{}' in {}{}", key, what, did_you_mean(key, allowed)),
           fmt::format(" (expected one of: {}){}", fmt::join(allowed, ", "), hint));
    }
    if (!seen.insert(key).second) fail(entry.first, fmt::format("duplicate key '{}' in {}", key, what));
  }
}

double YamlReader::number(const YAML::Node& node, const std::string& what, Range range) const {
  double value = 0.0;
  // What a message shows as the value: the text, and for an expression what it came to and when.
  std::string shown = node.IsScalar() ? node.Scalar() : std::string();
  if (!node.IsScalar()) fail(node, fmt::format("{} must be a number (got {})", what, describe_yaml(node)));
  if (!YAML::convert<double>::decode(node, value)) {
    // yaml-cpp refuses a number beyond double's range (1e400), which would then read as a bad
    // expression; say what is really wrong.
    char* end = nullptr;
    errno = 0;
    std::strtod(node.Scalar().c_str(), &end);
    if (errno == ERANGE && end != node.Scalar().c_str() && *end == '\0') {
      fail(node, fmt::format("{} must be a number within +-{:g}, the float range (got {})", what, kMaxSceneNumber,
                             node.Scalar()));
    }
    try {
      value = evaluate_expression(node.Scalar(), {{"t", time_}});
      shown = fmt::format("{} = {:g} at t = {:g}", node.Scalar(), value, time_);
      // A second time a second later tells whether the number moves with t (a preview's slider).
      if (!read_time_ && evaluate_expression(node.Scalar(), {{"t", time_ + 1.0}}) != value) read_time_ = true;
    } catch (const ExpressionError& e) {
      fail(node, fmt::format("{} must be a number or an expression of the time t (got '{}': {}){}", what, node.Scalar(),
                             e.what(), split_expression_hint(node.Scalar())));
    }
  }
  if (!std::isfinite(value)) fail(node, fmt::format("{} must be finite (got {})", what, shown));
  // The device computes in float: a larger value would become inf there, and as a literal of the
  // generated program "inff", which OpenCL C cannot parse (found by tests/fuzz/scene_fuzzer.cpp).
  if (std::abs(value) > kMaxSceneNumber) {
    fail(node, fmt::format("{} must be within +-{:g}, the float range (got {})", what, kMaxSceneNumber, shown));
  }
  if (!range.contains(value)) fail(node, fmt::format("{} must be {} (got {})", what, range.describe(), shown));
  return value;
}

int YamlReader::integer(const YAML::Node& node, const std::string& what, Range range) const {
  // Decimal digits only, as YAML 1.2 reads them: yaml-cpp would take 010 for octal 8 and 0x40 for 64.
  const std::string text = node.IsScalar() ? node.Scalar() : std::string();
  const std::size_t sign = !text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0;
  if (text.size() == sign || text.find_first_not_of("0123456789", sign) != std::string::npos) {
    fail(node, fmt::format("{} must be an integer in decimal digits (got {})", what, describe_yaml(node)));
  }
  long long value = 0;
  const char* digits = text.data() + (text[0] == '+' ? 1 : 0);
  const bool too_large = std::from_chars(digits, text.data() + text.size(), value).ec == std::errc::result_out_of_range;
  if (too_large || !range.contains(static_cast<double>(value))) {
    fail(node, fmt::format("{} must be {} (got {})", what, range.describe(), node.Scalar()));
  }
  return static_cast<int>(value);
}

std::string YamlReader::text(const YAML::Node& node, const std::string& what) const {
  if (!node.IsScalar()) fail(node, fmt::format("{} must be text (got {})", what, describe_yaml(node)));
  return node.Scalar();
}

bool YamlReader::boolean(const YAML::Node& node, const std::string& what) const {
  if (node.IsScalar() && node.Scalar() == "true") return true;
  if (node.IsScalar() && node.Scalar() == "false") return false;
  fail(node, fmt::format("{} must be true or false (got {})", what, describe_yaml(node)));
}

glm::dvec3 YamlReader::vec3(const YAML::Node& node, const std::string& what, Range range) const {
  if (!node.IsSequence() || node.size() != 3) {
    fail(node, fmt::format("{} must be a list of 3 numbers [x, y, z] (got {}){}", what,
                           node.IsSequence() ? fmt::format("{} items", node.size()) : describe_yaml(node),
                           glsl_vector_hint(node, key_of(what))));
  }
  return {number(node[0], what + "[0]", range), number(node[1], what + "[1]", range),
          number(node[2], what + "[2]", range)};
}

glm::dvec3 YamlReader::color(const YAML::Node& node, const std::string& what, bool warn_past_plausible) const {
  const std::string& text = node.IsScalar() ? node.Scalar() : std::string();
  const bool is_word = !text.empty() && std::all_of(text.begin(), text.end(),
                                                    [](unsigned char c) { return std::isalpha(c) || c == '_'; });
  const std::string glsl = glsl_vector_hint(node, key_of(what));
  if ((is_word && text != "t" && text != "pi") || !glsl.empty()) {
    fail(node, fmt::format(
                   "{} must be a color: [r, g, b], linear with 1 the full channel, or one number for gray (got '{}'){}",
                   what, text, glsl));
  }
  const glm::dvec3 color =
      node.IsScalar() ? glm::dvec3(number(node, what, Range::non_negative())) : vec3(node, what, Range::non_negative());
  if (warn_past_plausible && std::max({color.r, color.g, color.b}) > kPlausibleColor) {
    // Without the value, so that an animated color warns once, not once a frame.
    log_warning(
        fmt::format("{}: {} has a channel above {:g}: colors are linear with 1 the full channel (as in a shader), so "
                    "this one blows out; [255, 0, 0] red is [1, 0, 0]",
                    where(node), what, kPlausibleColor));
  }
  return color;
}

int YamlReader::choice_of(const YAML::Node& node, const std::string& what, const char* const* names,
                          std::size_t count) const {
  const std::string value = text(node, what);
  std::vector<std::string_view> options;
  for (std::size_t i = 0; i < count; ++i) {
    if (value == names[i]) return static_cast<int>(i);
    options.emplace_back(names[i]);
  }
  fail(node, fmt::format("{} must be one of {} (got '{}'){}", what, fmt::join(options, ", "), value,
                         did_you_mean(value, options)));
}

void YamlReader::optional_number(const YAML::Node& map, const char* key, const std::string& what, double& out,
                                 Range range) const {
  if (const YAML::Node value = map[key]) out = number(value, what, range);
}

void YamlReader::optional_vec3(const YAML::Node& map, const char* key, const std::string& what, glm::dvec3& out,
                               Range range) const {
  if (const YAML::Node value = map[key]) out = vec3(value, what, range);
}

YAML::Node YamlReader::required(const YAML::Node& map, const char* key, const std::string& what) const {
  const YAML::Node value = map[key];
  if (!value) fail(map, fmt::format("{} is required", what));
  return value;
}

}  // namespace clmarch
