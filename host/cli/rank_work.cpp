// The rank's loop over its units.
#include "cli/rank_work.hpp"

#include "cli/error_report.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "distributed/mpi_world.hpp"

#include <fmt/format.h>

namespace clmarch {
namespace {
bool g_every_rank_stopped = false;
}  // namespace

bool every_rank_stopped() { return g_every_rank_stopped; }

void render_units(WorkQueue& queue, const std::function<void(int unit)>& render, const UnitName& describe) {
  const MpiWorld& world = mpi_world();
  std::optional<int> own_failure;
  // A copy, not a reference: set_error_context below changes what error_context() refers to.
  const std::string rank_context = error_context();  // NOLINT(performance-unnecessary-copy-initialization)
  while (const std::optional<int> unit = queue.next()) {
    if (!world.distributed()) {
      render(*unit);
      continue;
    }
    set_error_context(fmt::format("{}, {}", rank_label(world.rank, world.host), describe(*unit)));
    const int code = run_reporting_errors([&] {
      render(*unit);
      return 0;
    });
    set_error_context(rank_context);
    if (code == 0) continue;
    // mpirun stops every rank with SIGTERM: no rank is left to wait for.
    if (cancellation_requested().load()) throw RankFailure(code, "");
    queue.failed(*unit, code);
    own_failure = code;
    break;
  }
  const std::optional<UnitFailure> failure = queue.finish();
  g_every_rank_stopped = true;
  // Rank 0 stopped waiting for the others because the job is being ended.
  throw_if_cancelled();
  if (own_failure) throw RankFailure(*own_failure, "");
  if (failure) {
    throw RankFailure(
        failure->exit_code,
        fmt::format("clmarch: {} failed at {} (exit code {}); the other ranks finished what they held and stopped",
                    rank_label(failure->rank, failure->host), describe(failure->unit), failure->exit_code));
  }
}

}  // namespace clmarch
