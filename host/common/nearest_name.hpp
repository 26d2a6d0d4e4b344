// "Did you mean": the valid name nearest a mistyped one.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace clmarch {

/// The name among candidates fewest single-character edits (insert, delete, substitute, swap of
/// neighbours) from typed, if that is at most a third of its length (at least 1, and at most 3);
/// else empty. Case is ignored.
std::string nearest_name(std::string_view typed, const std::vector<std::string_view>& candidates);

/// " (did you mean 'NAME'?)" for nearest_name, or empty.
std::string did_you_mean(std::string_view typed, const std::vector<std::string_view>& candidates);

}  // namespace clmarch
