// The files clmarch-docgen writes from the command line's model: the bash, zsh and fish completions
// and the man page.
#pragma once

#include "cli/docgen/command_model.hpp"

#include <string>

namespace clmarch::docgen {

/// For share/bash-completion/completions/clmarch: defines _clmarch and binds it to clmarch.
std::string bash_completion(const ProgramModel& model);

/// For share/zsh/vendor-completions/_clmarch (#compdef clmarch).
std::string zsh_completion(const ProgramModel& model);

/// For share/fish/vendor_completions.d/clmarch.fish.
std::string fish_completion(const ProgramModel& model);

/// Where the man page says the installed files are.
struct InstalledPaths {
  /// The example scenes, e.g. /usr/share/clmarch/scenes.
  std::string scenes;
  /// README.md and CHANGELOG.md, e.g. /usr/share/doc/clmarch.
  std::string docs;
};

/// clmarch.1 in man(7) roff.
std::string man_page(const ProgramModel& model, const InstalledPaths& paths);

}  // namespace clmarch::docgen
