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

}  // namespace clmarch
