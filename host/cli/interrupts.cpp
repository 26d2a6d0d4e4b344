// The signal handlers. They only touch lock-free atomics and call unlink() and _exit(), all
// async-signal-safe; they may run on any thread (PoCL's and TBB's workers included).
#include "cli/interrupts.hpp"

#include "common/cancellation.hpp"
#include "common/pending_file.hpp"

#include <atomic>
#include <csignal>

#include <unistd.h>

namespace clmarch {
namespace {

std::atomic<int> g_first_signal{0};

extern "C" void on_interrupt(int signal) {
  int none = 0;
  if (g_first_signal.compare_exchange_strong(none, signal)) {
    cancellation_requested().store(true);
    return;
  }
  // Second signal: the user does not want to wait for the current chunk or row to finish.
  remove_pending_file_in_signal_handler();
  _exit(128 + g_first_signal.load());
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action = {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  // Restart interrupted system calls: PoCL, TBB and OpenImageIO do not expect EINTR.
  action.sa_flags = SA_RESTART;
  for (int signal : {SIGINT, SIGTERM}) {
    struct sigaction previous = {};
    sigaction(signal, nullptr, &previous);
    // A signal the parent ignores stays ignored (`cmd &` in a script, whose shell ignores SIGINT
    // for background jobs): Ctrl-C in that terminal is meant for the foreground job, not for us.
    if (previous.sa_handler == SIG_IGN) continue;
    sigaction(signal, &action, nullptr);
  }
  std::signal(SIGXFSZ, SIG_IGN);
}

int interrupted_exit_code() {
  const int signal = g_first_signal.load();
  return 128 + (signal != 0 ? signal : SIGINT);
}

}  // namespace clmarch
