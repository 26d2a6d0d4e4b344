// The clmarch executable run in the background (to signal it while it works) or on a pseudo
// terminal (to see what it draws only for a person at a terminal).
#pragma once

#include "support/test_support.hpp"

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include <sys/types.h>

namespace clmarch::testing {

/// clmarch started with args; stdout and stderr go to files, stdin is /dev/null.
class ClmarchProcess {
 public:
  /// environment holds extra NAME=VALUE settings; sigint_ignored starts clmarch with SIGINT
  /// ignored, as a script's shell starts its background jobs; launcher (a program by its full
  /// path, and its arguments) runs clmarch, e.g. mpirun -n 3.
  explicit ClmarchProcess(const std::vector<std::string>& args, const std::vector<std::string>& environment = {},
                          bool sigint_ignored = false, const std::vector<std::string>& launcher = {});
  pid_t pid() const { return pid_; }
  /// Kills the process if it still runs.
  ~ClmarchProcess();
  ClmarchProcess(const ClmarchProcess&) = delete;
  ClmarchProcess& operator=(const ClmarchProcess&) = delete;

  /// Waits until stderr contains text; false on timeout or if the process ended first.
  bool wait_for_stderr(const std::string& text, std::chrono::milliseconds timeout);
  void send_signal(int signal);
  /// The exit code (128 + signal when a signal killed it), or nothing on timeout.
  std::optional<int> wait(std::chrono::milliseconds timeout);
  std::string err() const;
  std::string out() const;

 private:
  TempDir capture_;
  pid_t pid_ = -1;
  bool running_ = false;
  int exit_code_ = -1;
};

/// Runs clmarch with its stderr on a pseudo terminal; returns what appeared there (stdout is
/// discarded) and the exit code.
CommandResult run_clmarch_on_terminal(const std::vector<std::string>& args);

}  // namespace clmarch::testing
