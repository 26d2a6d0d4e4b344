// The signal handlers. They only touch lock-free atomics and call write(), unlink() and _exit(),
// all async-signal-safe; they may run on any thread (PoCL's and TBB's workers included).
#include "cli/interrupts.hpp"

#include "common/cancellation.hpp"
#include "common/interrupt_note.hpp"
#include "common/pending_file.hpp"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstring>

#include <pthread.h>
#include <unistd.h>

namespace clmarch {
namespace {

std::atomic<int> g_first_signal{0};

/// The line the first signal prints when it ends the process at once, and whether it always does
/// (exit_at_first_signal); set before the handlers can see them change.
char g_message[512] = "clmarch: interrupted\n";
std::size_t g_message_length = sizeof "clmarch: interrupted\n" - 1;
std::atomic<bool> g_exit_at_once{false};

extern "C" void on_interrupt(int signal) {
  int none = 0;
  if (g_first_signal.compare_exchange_strong(none, signal)) {
    cancellation_requested().store(true);
    if (blocking_calls_in_progress().load() == 0 && !g_exit_at_once.load()) return;
    // Inside a call with no cancellation point (BlockingCall), or a rank of an MPI job: stopping
    // now loses nothing.
    [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, g_message, g_message_length);
    write_interrupt_note();
  }
  // A second signal: the user does not want to wait for the current chunk or row to finish.
  remove_pending_files_in_signal_handler();
  _exit(128 + g_first_signal.load());
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action = {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  // Restart interrupted system calls: PoCL, TBB and OpenImageIO do not expect EINTR.
  action.sa_flags = SA_RESTART;
  sigset_t ignored;
  sigemptyset(&ignored);
  for (int signal : {SIGINT, SIGTERM}) {
    struct sigaction previous = {};
    sigaction(signal, nullptr, &previous);
    // A signal the parent ignores stays ignored (`cmd &` in a script, whose shell ignores SIGINT
    // for background jobs): Ctrl-C in that terminal is meant for the foreground job, not for us.
    if (previous.sa_handler == SIG_IGN) {
      sigaddset(&ignored, signal);
      continue;
    }
    sigaction(signal, &action, nullptr);
  }
  // Blocked as well: PoCL's compiler (LLVM) puts its own handler over an ignored signal to remove
  // its temporary files, which fails the build in progress. A blocked signal reaches no handler;
  // the threads the drivers start later inherit the mask.
  pthread_sigmask(SIG_BLOCK, &ignored, nullptr);
  std::signal(SIGXFSZ, SIG_IGN);
}

void exit_at_first_signal(std::string_view message) {
  const std::size_t length = std::min(message.size(), sizeof g_message - 2);
  std::memcpy(g_message, message.data(), length);
  g_message[length] = '\n';
  g_message_length = length + 1;
  g_exit_at_once.store(true);
}

int interrupted_exit_code() {
  const int signal = g_first_signal.load();
  return 128 + (signal != 0 ? signal : SIGINT);
}

}  // namespace clmarch
