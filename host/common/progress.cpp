// The progress line.
#include "common/progress.hpp"

#include "common/cancellation.hpp"
#include "common/log.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <mutex>
#include <utility>

#include <unistd.h>

namespace clmarch {

namespace {
bool g_draw_anyway = false;
std::mutex g_progress_sink_mutex;
ProgressSink g_progress_sink;

/// The sink, if one is set (a copy: it may be replaced meanwhile).
ProgressSink current_sink() {
  const std::lock_guard lock(g_progress_sink_mutex);
  return g_progress_sink;
}
/// Progress lines alive: under MPI only the outermost one draws (the frames or tiles of all ranks,
/// not the chunks of rank 0's own render).
std::atomic<int> g_live_lines{0};
}  // namespace

bool progress_enabled() { return verbosity() != Verbosity::Quiet && (g_draw_anyway || isatty(STDERR_FILENO) == 1); }

void draw_progress_anyway() { g_draw_anyway = true; }

void set_progress_sink(ProgressSink sink) {
  const std::lock_guard lock(g_progress_sink_mutex);
  g_progress_sink = std::move(sink);
}

ProgressLine::ProgressLine(std::string label, long long total, double rays_per_unit)
    : label_(std::move(label)),
      total_(total),
      rays_per_unit_(rays_per_unit),
      enabled_(progress_enabled()),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {
  const bool nested = g_live_lines.fetch_add(1) > 0;
  if (g_draw_anyway && nested) enabled_ = false;
}

ProgressLine::~ProgressLine() {
  g_live_lines.fetch_sub(1);
  if (drawn_ && !g_draw_anyway) std::fputs("\r\033[K", stderr);
}

void ProgressLine::advance(long long done) {
  throw_if_cancelled();
  count(done);
}

void ProgressLine::count(long long done) {
  const long long now_done = done_ += done;
  if (const ProgressSink sink = current_sink()) {
    // Other threads skip a report while one is being made, but the last one always comes.
    const bool last = now_done >= total_;
    std::unique_lock lock(draw_, std::defer_lock);
    if (last) {
      lock.lock();
    } else if (!lock.try_lock()) {
      return;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!last && now - last_draw_ < std::chrono::milliseconds(250)) return;
    last_draw_ = now;
    sink(label_, now_done, total_);
    return;
  }
  if (!enabled_) return;
  std::unique_lock lock(draw_, std::try_to_lock);
  if (!lock) return;
  const auto now = std::chrono::steady_clock::now();
  // Work shorter than a second stays silent.
  const auto interval = std::chrono::milliseconds(g_draw_anyway ? 2000 : 250);
  if (now - start_ < std::chrono::seconds(1) || now - last_draw_ < interval) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fraction = static_cast<double>(now_done) / static_cast<double>(total_);
  const double left = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  const std::string rate =
      rays_per_unit_ > 0.0 ? fmt::format(", {:.3g} rays/s", rays_per_unit_ * static_cast<double>(now_done) / elapsed)
                           : "";
  const std::string line =
      fmt::format("{}: {:.0f}% ({}/{}){}, {:.1f} s left", label_, 100.0 * fraction, now_done, total_, rate, left);
  // Through mpirun's pipe, whole lines: the other ranks' lines come between them.
  std::fputs((g_draw_anyway ? "clmarch: " + line + "\n" : "\r\033[K" + line).c_str(), stderr);
  drawn_ = true;
}

}  // namespace clmarch
