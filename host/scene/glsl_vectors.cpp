// Spotting GLSL vector constructors in scene text, for the loader's hints.
#include "scene/glsl_vectors.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>
#include <regex>
#include <vector>

namespace clmarch {
namespace {

/// One argument as YAML spells it: a number in its shortest form (".5" is 0.5), else as written.
std::string yaml_spelling(std::string argument) {
  const std::size_t first = argument.find_first_not_of(" \t");
  const std::size_t last = argument.find_last_not_of(" \t");
  argument = first == std::string::npos ? std::string() : argument.substr(first, last - first + 1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(argument.data(), argument.data() + argument.size(), value);
  return error == std::errc() && end == argument.data() + argument.size() ? fmt::format("{}", value) : argument;
}

const std::regex& constructor() {
  static const std::regex pattern(R"([biud]?vec[234]\s*\(([^()]*)\))");
  return pattern;
}

}  // namespace

std::string glsl_vectors_as_yaml(std::string_view view) {
  const std::string text(view);
  std::string out;
  auto rest = text.cbegin();
  for (std::sregex_iterator it(text.begin(), text.end(), constructor()), end; it != end; ++it) {
    out.append(rest, (*it)[0].first);
    std::vector<std::string> items;
    const std::string arguments = (*it)[1].str();
    std::size_t start = 0;
    for (std::size_t comma; (comma = arguments.find(',', start)) != std::string::npos; start = comma + 1)
      items.push_back(yaml_spelling(arguments.substr(start, comma - start)));
    items.push_back(yaml_spelling(arguments.substr(start)));
    out += fmt::format("[{}]", fmt::join(items, ", "));
    rest = (*it)[0].second;
  }
  if (rest == text.cbegin()) return {};
  out.append(rest, text.cend());
  return out;
}

bool starts_glsl_vector(std::string_view text) {
  static const std::regex start(R"(^\s*[biud]?vec[234]\s*\()");
  return std::regex_search(text.begin(), text.end(), start);
}

}  // namespace clmarch
