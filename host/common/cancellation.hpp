// Cooperative cancellation of long renders (Ctrl-C): long loops poll it between units of work.
#pragma once

#include <atomic>
#include <stdexcept>

namespace clmarch {

/// Thrown by throw_if_cancelled once cancellation was requested.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

/// Set from a signal handler; async-signal-safe (lock-free atomic).
inline std::atomic<bool>& cancellation_requested() {
  static std::atomic<bool> requested{false};
  return requested;
}

inline void throw_if_cancelled() {
  if (cancellation_requested().load(std::memory_order_relaxed)) throw Cancelled();
}

/// How many BlockingCall scopes are open; read by the signal handler (lock-free atomic).
inline std::atomic<int>& blocking_calls_in_progress() {
  static std::atomic<int> calls{0};
  return calls;
}

/// Brackets a call that can block for long with no cancellation point inside and has nothing to
/// write or keep: an OpenCL program build (minutes for a scene of thousands of nodes on PoCL),
/// opening a FIFO whose writer never comes. A first Ctrl-C during it ends the process at once
/// instead of after the call returns (cli/interrupts.cpp). Throws Cancelled if cancellation was
/// requested already, so that a signal just before the call is not lost either.
class BlockingCall {
 public:
  BlockingCall() {
    blocking_calls_in_progress().fetch_add(1);
    if (cancellation_requested().load()) {
      blocking_calls_in_progress().fetch_sub(1);
      throw Cancelled();
    }
  }
  ~BlockingCall() { blocking_calls_in_progress().fetch_sub(1); }
  BlockingCall(const BlockingCall&) = delete;
  BlockingCall& operator=(const BlockingCall&) = delete;
};

}  // namespace clmarch
