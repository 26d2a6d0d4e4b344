// The scoped SIGINT handler: it only stores lock-free atomics (async-signal-safe).
#include "interrupt_scope.hpp"

#include "common/cancellation.hpp"

#include <pybind11/pybind11.h>

#include <atomic>

namespace clmarch::python {
namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_sigint(int) {
  g_interrupted.store(true);
  cancellation_requested().store(true);
}

bool on_main_thread() {
  const pybind11::module_ threading = pybind11::module_::import("threading");
  const pybind11::object main_ident = threading.attr("main_thread")().attr("ident");
  return main_ident.equal(threading.attr("get_ident")());
}

}  // namespace

InterruptScope::InterruptScope() {
  g_interrupted.store(false);
  cancellation_requested().store(false);
  if (!on_main_thread()) return;
  struct sigaction action = {};
  action.sa_handler = on_sigint;
  sigemptyset(&action.sa_mask);
  // PoCL, TBB and OpenImageIO do not expect EINTR.
  action.sa_flags = SA_RESTART;
  installed_ = sigaction(SIGINT, &action, &previous_) == 0;
}

InterruptScope::~InterruptScope() {
  if (installed_) sigaction(SIGINT, &previous_, nullptr);
  cancellation_requested().store(false);
}

bool InterruptScope::interrupted() { return g_interrupted.load(); }

}  // namespace clmarch::python
