// clmarch-docgen: writes clmarch's shell completions and man page from its command line
// (cli/command_line), so that the build keeps them in step with the options. Not installed.
#include "cli/command_line.hpp"
#include "cli/docgen/command_model.hpp"
#include "cli/docgen/writers.hpp"
#include "common/atomic_file.hpp"

#include <exception>
#include <filesystem>
#include <iostream>

int main(int argc, char** argv) {
  using namespace clmarch;
  if (argc != 4) {
    std::cerr << "usage: clmarch-docgen OUT_DIR SCENES_DIR DOCS_DIR\n"
                 "  writes OUT_DIR/clmarch.bash, _clmarch (zsh), clmarch.fish and clmarch.1; the man page names\n"
                 "  SCENES_DIR and DOCS_DIR as the installed example scenes and documents\n";
    return 2;
  }
  try {
    CommandLine line;
    const docgen::ProgramModel model = docgen::describe_program(line.app, clmarch_version());
    const std::filesystem::path out(argv[1]);
    write_file_atomically(out / "clmarch.bash", docgen::bash_completion(model));
    write_file_atomically(out / "_clmarch", docgen::zsh_completion(model));
    write_file_atomically(out / "clmarch.fish", docgen::fish_completion(model));
    write_file_atomically(out / "clmarch.1", docgen::man_page(model, {argv[2], argv[3]}));
  } catch (const std::exception& e) {
    std::cerr << "clmarch-docgen: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
