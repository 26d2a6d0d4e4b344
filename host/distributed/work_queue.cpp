// The work queue: a plain loop for one process; over MPI, a coordinator on rank 0 answering each
// rank's "done, what next?" with the next unit. Messages are a fixed header (MPI_BYTE) and, for a
// tile, its pixels (MPI_FLOAT) right after it.
#include "distributed/work_queue.hpp"

#include "common/cancellation.hpp"
#include "common/interrupt_note.hpp"
#include "distributed/mpi_world.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#if CLMARCH_HAVE_MPI
#include <mpi.h>
#endif

namespace clmarch {
namespace {

/// The single process: units in order.
class LocalQueue final : public WorkQueue {
 public:
  LocalQueue(int count, UnitSink sink) : count_(count), sink_(std::move(sink)) {}
  std::optional<int> next() override {
    if (failure_ || next_ >= count_) return std::nullopt;
    return next_++;
  }
  void done(int unit, const UnitFigures& figures, std::span<const float> payload) override {
    UnitFigures mine = figures;
    mine.host = mpi_world().host;
    sink_(0, unit, mine, payload);
  }
  void failed(int unit, int exit_code) override {
    if (!failure_) failure_ = UnitFailure{0, mpi_world().host, unit, exit_code};
  }
  std::optional<UnitFailure> finish() override { return failure_; }

 private:
  int count_;
  int next_ = 0;
  UnitSink sink_;
  std::optional<UnitFailure> failure_;
};

#if CLMARCH_HAVE_MPI

enum Tag : int { kTagReport = 2701, kTagPayload = 2702, kTagAssign = 2703 };
enum ReportKind : int { kReady = 0, kDone = 1, kFailed = 2 };

/// What a rank tells the coordinator: ready for its first unit, a unit done (a request for the
/// next one too), or a unit failed. Plain bytes on the wire: every rank runs the same executable.
struct Report {
  int kind = kReady;
  int unit = -1;
  int exit_code = 0;
  int lanes = 1;
  int chunks = 0;
  int payload_floats = 0;
  double pixels = 0.0;
  double kernel_ms = 0.0;
  double build_ms = 0.0;
  double rays_per_s = 0.0;
  std::uint64_t steps = 0;
  std::uint64_t wall_steps = 0;
  std::uint64_t coarse_steps = 0;
  std::uint64_t out_of_steps = 0;
  std::uint64_t out_of_distance = 0;
  char device[256] = {};
  char host[128] = {};
  char literals[8] = {};
  char stages[8] = {};
};

template <std::size_t N>
void copy_text(char (&to)[N], const std::string& from) {
  const std::size_t n = std::min(from.size(), N - 1);
  std::memcpy(to, from.data(), n);
  to[n] = '\0';
}

Report report_of(int kind, int unit, const UnitFigures* figures, std::size_t payload_floats) {
  if (payload_floats > static_cast<std::size_t>(INT_MAX)) {
    throw std::length_error("a tile of more than 2^31 floats: render the image over more ranks or smaller tiles");
  }
  Report r;
  r.kind = kind;
  r.unit = unit;
  r.payload_floats = static_cast<int>(payload_floats);
  copy_text(r.host, mpi_world().host);
  if (figures) {
    const RenderStats& s = figures->stats;
    r.lanes = s.lanes;
    r.chunks = s.chunks;
    r.pixels = figures->pixels;
    r.kernel_ms = s.kernel_ms;
    r.build_ms = s.build_ms;
    r.rays_per_s = s.rays_per_s;
    r.steps = s.steps;
    r.wall_steps = s.wall_steps;
    r.coarse_steps = s.coarse_steps;
    r.out_of_steps = s.out_of_steps;
    r.out_of_distance = s.out_of_distance;
    copy_text(r.device, s.device);
    copy_text(r.literals, s.literals);
    copy_text(r.stages, s.stages);
  }
  return r;
}

UnitFigures figures_of(const Report& r) {
  UnitFigures f;
  f.pixels = r.pixels;
  f.host = r.host;
  RenderStats& s = f.stats;
  s.device = r.device;
  s.literals = r.literals;
  s.stages = r.stages;
  s.lanes = r.lanes;
  s.chunks = r.chunks;
  s.kernel_ms = r.kernel_ms;
  s.build_ms = r.build_ms;
  s.rays_per_s = r.rays_per_s;
  s.steps = r.steps;
  s.wall_steps = r.wall_steps;
  s.coarse_steps = r.coarse_steps;
  s.out_of_steps = r.out_of_steps;
  s.out_of_distance = r.out_of_distance;
  return f;
}

/// Waits for request without holding the MPI lock, and without spinning a core: the ranks of a
/// small machine share its cores with the renders.
void wait_for(MPI_Request& request) {
  for (;;) {
    int complete = 0;
    {
      const std::lock_guard lock(mpi_mutex());
      MPI_Test(&request, &complete, MPI_STATUS_IGNORE);
    }
    if (complete) return;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

/// Rank 0: hands out units to its own main thread (next()) and, on its coordinator thread, to the
/// other ranks as their reports come in.
class CoordinatorQueue final : public WorkQueue {
 public:
  CoordinatorQueue(int count, UnitSink sink, UnitName name)
      : count_(count), sink_(std::move(sink)), name_(std::move(name)) {
    in_flight_.assign(static_cast<std::size_t>(mpi_world().size), -1);
    hosts_.assign(static_cast<std::size_t>(mpi_world().size), "");
    hosts_[0] = mpi_world().host;
    thread_ = std::thread([this] { serve(); });
  }
  ~CoordinatorQueue() override {
    stop_.store(true);
    if (thread_.joinable()) thread_.join();
    set_interrupt_note("");
  }
  std::optional<int> next() override {
    const int unit = take(0);
    if (unit < 0) return std::nullopt;
    return unit;
  }
  void done(int unit, const UnitFigures& figures, std::span<const float> payload) override {
    hold(0, -1);
    UnitFigures mine = figures;
    mine.host = mpi_world().host;
    sink_(0, unit, mine, payload);
  }
  void failed(int unit, int exit_code) override { record_failure(UnitFailure{0, mpi_world().host, unit, exit_code}); }
  std::optional<UnitFailure> finish() override {
    if (thread_.joinable()) thread_.join();
    const std::lock_guard lock(state_);
    return failure_;
  }

 private:
  /// The next unit for rank, or -1: all handed out, the job failed or is being interrupted.
  int take(int rank) {
    int unit = -1;
    {
      const std::lock_guard lock(state_);
      if (failure_ || cancellation_requested().load() || next_ >= count_) return -1;
      unit = next_++;
    }
    hold(rank, unit);
    return unit;
  }

  /// Records that rank holds unit (-1: none), and says so in the interrupt note: when mpirun ends
  /// the job because a rank died, rank 0's last words name the units that were in progress.
  void hold(int rank, int unit) {
    const std::lock_guard lock(state_);
    in_flight_[static_cast<std::size_t>(rank)] = unit;
    std::string note;
    for (std::size_t r = 0; r < in_flight_.size(); ++r) {
      if (in_flight_[r] < 0) continue;
      note += fmt::format("{}{}: {}", note.empty() ? "in progress: " : "; ", rank_label(static_cast<int>(r), hosts_[r]),
                          name_(in_flight_[r]));
    }
    set_interrupt_note(note);
  }

  void record_failure(const UnitFailure& failure) {
    const std::lock_guard lock(state_);
    if (!failure_) failure_ = failure;
  }

  /// Answers reports until every other rank has been told to stop (or has failed).
  void serve() {
    const int others = mpi_world().size - 1;
    int stopped = 0;
    std::vector<float> payload;
    // An interrupted job (Ctrl-C, or mpirun ending it for a lost rank) has no one left to wait for.
    while (stopped < others && !stop_.load() && !cancellation_requested().load()) {
      Report report;
      int source = -1;
      {
        const std::lock_guard lock(mpi_mutex());
        int arrived = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, kTagReport, MPI_COMM_WORLD, &arrived, &status);
        if (arrived) {
          source = status.MPI_SOURCE;
          MPI_Recv(&report, sizeof report, MPI_BYTE, source, kTagReport, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          payload.resize(static_cast<std::size_t>(report.payload_floats));
          if (report.payload_floats > 0) {
            MPI_Recv(payload.data(), report.payload_floats, MPI_FLOAT, source, kTagPayload, MPI_COMM_WORLD,
                     MPI_STATUS_IGNORE);
          }
        }
      }
      if (source < 0) {
        // Reports come once a unit is done (tens of ms at least): a millisecond's nap costs no time
        // and leaves the core to the renders.
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        continue;
      }
      {
        const std::lock_guard lock(state_);
        hosts_[static_cast<std::size_t>(source)] = report.host;
      }
      if (report.kind == kFailed) {
        hold(source, -1);
        record_failure(UnitFailure{source, report.host, report.unit, report.exit_code});
        ++stopped;
        continue;
      }
      if (report.kind == kDone) {
        hold(source, -1);
        sink_(source, report.unit, figures_of(report), std::span<const float>(payload.data(), payload.size()));
      }
      const int unit = take(source);
      {
        const std::lock_guard lock(mpi_mutex());
        MPI_Send(&unit, 1, MPI_INT, source, kTagAssign, MPI_COMM_WORLD);
      }
      if (unit < 0) ++stopped;
    }
  }

  int count_;
  UnitSink sink_;
  UnitName name_;
  std::mutex state_;
  int next_ = 0;
  std::optional<UnitFailure> failure_;
  /// The unit each rank holds, -1 for none, and the ranks' hosts as their reports say.
  std::vector<int> in_flight_;
  std::vector<std::string> hosts_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

/// Ranks 1 and up: ask rank 0 for units, report them done with their payload.
class RemoteQueue final : public WorkQueue {
 public:
  std::optional<int> next() override {
    if (stopped_) return std::nullopt;
    if (!asked_) send(report_of(kReady, -1, nullptr, 0), {});
    asked_ = false;
    int unit = -1;
    MPI_Request request;
    {
      const std::lock_guard lock(mpi_mutex());
      MPI_Irecv(&unit, 1, MPI_INT, 0, kTagAssign, MPI_COMM_WORLD, &request);
    }
    wait_for(request);
    if (unit < 0) {
      stopped_ = true;
      return std::nullopt;
    }
    return unit;
  }
  void done(int unit, const UnitFigures& figures, std::span<const float> payload) override {
    send(report_of(kDone, unit, &figures, payload.size()), payload);
    asked_ = true;
  }
  void failed(int unit, int exit_code) override {
    Report report = report_of(kFailed, unit, nullptr, 0);
    report.exit_code = exit_code;
    send(report, {});
    stopped_ = true;
  }
  std::optional<UnitFailure> finish() override { return std::nullopt; }

 private:
  void send(const Report& report, std::span<const float> payload) {
    const std::lock_guard lock(mpi_mutex());
    MPI_Send(&report, sizeof report, MPI_BYTE, 0, kTagReport, MPI_COMM_WORLD);
    if (!payload.empty()) {
      MPI_Send(payload.data(), static_cast<int>(payload.size()), MPI_FLOAT, 0, kTagPayload, MPI_COMM_WORLD);
    }
  }

  /// Whether the last report (a done) already asked for the next unit.
  bool asked_ = false;
  bool stopped_ = false;
};

#endif

}  // namespace

std::unique_ptr<WorkQueue> make_work_queue(int count, UnitSink sink, UnitName name) {
#if CLMARCH_HAVE_MPI
  if (mpi_world().distributed()) {
    if (mpi_world().rank == 0) return std::make_unique<CoordinatorQueue>(count, std::move(sink), std::move(name));
    return std::make_unique<RemoteQueue>();
  }
#else
  (void)name;
#endif
  return std::make_unique<LocalQueue>(count, std::move(sink));
}

}  // namespace clmarch
