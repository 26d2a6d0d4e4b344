// Ctrl-C during a long call from Python: while a scope is open on the main thread, SIGINT asks the
// work to stop at its next cancellation point (as the CLI's first Ctrl-C does) instead of waiting
// for Python's handler, which cannot run while the call holds the thread.
#pragma once

#include <csignal>

namespace clmarch::python {

class InterruptScope {
 public:
  /// Installs the handler when called on Python's main thread (signals reach Python's handlers
  /// there only), and clears a cancellation left from before.
  InterruptScope();
  /// Restores the previous handler and clears the cancellation, so the next call runs.
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

  /// Whether a SIGINT arrived while the scope was open.
  static bool interrupted();

 private:
  bool installed_ = false;
  struct sigaction previous_ = {};
};

}  // namespace clmarch::python
