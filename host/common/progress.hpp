// Progress of long work on stderr: a single self-rewriting line, only when stderr is a terminal
// and not with --quiet. Reporting progress is also a cancellation point (Ctrl-C).
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <functional>
#include <string>
#include <string_view>

namespace clmarch {

/// True when progress lines are drawn: stderr is a terminal (or draw_progress_anyway() was
/// called) and the verbosity is not Quiet.
bool progress_enabled();
/// Draws progress even though stderr is not a terminal: rank 0 of an MPI job, whose stderr mpirun
/// forwards to its own through a pipe. Then progress comes as whole lines, at most one every 2 s,
/// from the outermost progress line only (the frames or tiles of all ranks).
void draw_progress_anyway();

/// Where a library's caller takes progress instead of the line on stderr (the Python module hands
/// it to a Python function): called with the work's label and its units done and in all, at most
/// four times a second and once when all are done, from any thread; an empty sink restores the line.
using ProgressSink = std::function<void(std::string_view label, long long done, long long total)>;
void set_progress_sink(ProgressSink sink);

class ProgressLine {
 public:
  /// label names the work ("reference"); total counts its units (rows, tiles, frames), each of
  /// rays_per_unit rays (pixels), which the line turns into rays/s when it is > 0.
  ProgressLine(std::string label, long long total, double rays_per_unit = 0.0);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Adds done units; safe to call from any thread. Redraws at most four times a second.
  /// Throws Cancelled once cancellation was requested, so that every loop which reports progress
  /// (the OpenCL chunks, the reference's rows inside tbb::parallel_for) stops at its next unit.
  void advance(long long done = 1);
  /// advance() without its cancellation point: for a thread that must not throw (the coordinator
  /// of an MPI job counting the other ranks' units).
  void count(long long done = 1);

 private:
  std::string label_;
  long long total_;
  double rays_per_unit_;
  bool enabled_;
  std::atomic<long long> done_{0};
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  std::mutex draw_;
  bool drawn_ = false;
};

}  // namespace clmarch
