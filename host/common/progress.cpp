// The progress line.
#include "common/progress.hpp"

#include "common/cancellation.hpp"
#include "common/log.hpp"

#include <fmt/format.h>

#include <cstdio>

#include <unistd.h>

namespace clmarch {

bool progress_enabled() { return verbosity() != Verbosity::Quiet && isatty(STDERR_FILENO) == 1; }

ProgressLine::ProgressLine(std::string label, long long total, double rays_per_unit)
    : label_(std::move(label)), total_(total), rays_per_unit_(rays_per_unit), enabled_(progress_enabled()),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

ProgressLine::~ProgressLine() {
  if (drawn_) std::fputs("\r\033[K", stderr);
}

void ProgressLine::advance(long long done) {
  throw_if_cancelled();
  const long long now_done = done_ += done;
  if (!enabled_) return;
  std::unique_lock lock(draw_, std::try_to_lock);
  if (!lock) return;
  const auto now = std::chrono::steady_clock::now();
  // Work shorter than a second stays silent.
  if (now - start_ < std::chrono::seconds(1) || now - last_draw_ < std::chrono::milliseconds(250)) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fraction = static_cast<double>(now_done) / static_cast<double>(total_);
  const double left = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  const std::string rate =
      rays_per_unit_ > 0.0 ? fmt::format(", {:.3g} rays/s", rays_per_unit_ * static_cast<double>(now_done) / elapsed) : "";
  std::fputs(fmt::format("\r\033[K{}: {:.0f}% ({}/{}){}, {:.1f} s left", label_, 100.0 * fraction, now_done, total_, rate,
                         left)
                 .c_str(),
             stderr);
  drawn_ = true;
}

}  // namespace clmarch
