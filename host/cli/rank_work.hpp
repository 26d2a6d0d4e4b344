// The loop every rank of a render runs over the units (frames, tiles) a WorkQueue hands it, and
// how a failed unit ends the job.
#pragma once

#include "distributed/work_queue.hpp"

#include <functional>
#include <string>

namespace clmarch {

/// Calls render(unit) for each unit the queue hands this rank, then waits for every rank to stop.
/// In one process an error propagates as it is. Under MPI a unit's error is printed at once as
/// "clmarch: rank R on HOST, DESCRIBE(unit): MESSAGE", the queue stops handing out units (the
/// other ranks finish the ones they hold), and the rank throws RankFailure with the error's exit
/// code; rank 0 throws RankFailure naming the rank, host and unit that failed. An interrupted
/// rank (Ctrl-C or SIGTERM, which mpirun sends every rank) throws RankFailure at once, without
/// waiting for the others.
void render_units(WorkQueue& queue, const std::function<void(int unit)>& render, const UnitName& describe);

/// Whether render_units has returned: every rank has left the loop, and an error of this rank
/// now keeps no other rank waiting.
bool every_rank_stopped();

}  // namespace clmarch
