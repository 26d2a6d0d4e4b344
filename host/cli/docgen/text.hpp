// Small string helpers of the documentation writers.
#pragma once

#include <string>
#include <vector>

namespace clmarch::docgen {

/// words with separator between them.
std::string joined(const std::vector<std::string>& words, const std::string& separator);

/// text cut at each separator (no empty last part for a trailing separator).
std::vector<std::string> split(const std::string& text, char separator);

/// text without its leading and trailing spaces.
std::string trimmed(const std::string& text);

/// text with each character of specials preceded by a backslash.
std::string backslashed(const std::string& text, const std::string& specials);

}  // namespace clmarch::docgen
