// The stderr message levels.
#include "common/log.hpp"

#include <atomic>
#include <cstdio>
#include <mutex>
#include <set>
#include <string>
#include <utility>

namespace clmarch {
namespace {

std::atomic<Verbosity> g_verbosity{Verbosity::Normal};

std::mutex g_sink_mutex;
LogSink g_sink;

void write_line(LogLevel level, std::string_view line) {
  {
    const std::lock_guard lock(g_sink_mutex);
    if (g_sink) {
      g_sink(level, line);
      return;
    }
  }
  // One fputs per line so that lines of concurrent writers (TBB workers) do not interleave.
  std::string text = level == LogLevel::Warning ? "clmarch: warning: " : "clmarch: ";
  text.append(line).push_back('\n');
  std::fputs(text.c_str(), stderr);
}

}  // namespace

void set_verbosity(Verbosity verbosity) { g_verbosity.store(verbosity, std::memory_order_relaxed); }

Verbosity verbosity() { return g_verbosity.load(std::memory_order_relaxed); }

void set_log_sink(LogSink sink) {
  const std::lock_guard lock(g_sink_mutex);
  g_sink = std::move(sink);
}

void log_info(std::string_view line) {
  if (verbosity() != Verbosity::Quiet) write_line(LogLevel::Info, line);
}

void log_verbose(std::string_view line) {
  if (verbosity() == Verbosity::Verbose) write_line(LogLevel::Verbose, line);
}

void log_warning(std::string_view line) {
  static std::mutex mutex;
  static std::set<std::string, std::less<>> said;
  const std::lock_guard lock(mutex);
  if (verbosity() == Verbosity::Quiet || !said.emplace(line).second) return;
  write_line(LogLevel::Warning, line);
}

}  // namespace clmarch
