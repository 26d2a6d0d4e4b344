// The stderr message levels.
#include "common/log.hpp"

#include <atomic>
#include <cstdio>
#include <mutex>
#include <set>
#include <string>

namespace clmarch {
namespace {

std::atomic<Verbosity> g_verbosity{Verbosity::Normal};

void write_line(std::string_view line) {
  // One fputs per line so that lines of concurrent writers (TBB workers) do not interleave.
  std::string text = "clmarch: ";
  text.append(line).push_back('\n');
  std::fputs(text.c_str(), stderr);
}

}  // namespace

void set_verbosity(Verbosity verbosity) { g_verbosity.store(verbosity, std::memory_order_relaxed); }

Verbosity verbosity() { return g_verbosity.load(std::memory_order_relaxed); }

void log_info(std::string_view line) {
  if (verbosity() != Verbosity::Quiet) write_line(line);
}

void log_verbose(std::string_view line) {
  if (verbosity() == Verbosity::Verbose) write_line(line);
}

void log_warning(std::string_view line) {
  static std::mutex mutex;
  static std::set<std::string, std::less<>> said;
  const std::lock_guard lock(mutex);
  if (verbosity() == Verbosity::Quiet || !said.emplace(line).second) return;
  write_line(std::string("warning: ").append(line));
}

}  // namespace clmarch
