// Units of work (the frames of an animation, the tiles of rows of one image) handed out one at a
// time to whichever rank is free: a frame that costs more keeps its rank busy while the others
// take the next ones.
#pragma once

#include "render/opencl_renderer.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

namespace clmarch {

/// What a rank reports with a finished unit (its --stats figures).
struct UnitFigures {
  RenderStats stats;
  /// Pixels the unit rendered.
  double pixels = 0.0;
  /// The node of the rank that rendered it (filled in by the queue).
  std::string host;
};

/// A failed unit: who, where, which unit, and the exit code of its error.
struct UnitFailure {
  int rank = 0;
  std::string host;
  int unit = -1;
  int exit_code = 0;
};

/// Called on rank 0 for every finished unit, its own and the other ranks' (on the coordinator's
/// thread for theirs): the rank, the unit, its figures and its payload (the tile's pixels; empty
/// for frames, which each rank writes itself).
using UnitSink = std::function<void(int rank, int unit, const UnitFigures& figures, std::span<const float> payload)>;

/// Every rank's end of one job of units 0 .. count - 1. Rank 0 also runs the coordinator, on a
/// thread of its own, while its main thread renders units like any other rank.
class WorkQueue {
 public:
  virtual ~WorkQueue() = default;
  /// The next unit for this rank, or none once every unit is handed out or the job failed.
  virtual std::optional<int> next() = 0;
  /// Reports unit as finished (with the payload rank 0 gathers).
  virtual void done(int unit, const UnitFigures& figures, std::span<const float> payload) = 0;
  /// Reports that unit failed with exit_code (its message is already printed); the job hands out
  /// no more units, and the ranks finish what they hold.
  virtual void failed(int unit, int exit_code) = 0;
  /// Waits until every rank has stopped. On rank 0: the first failure, if any; elsewhere nothing.
  virtual std::optional<UnitFailure> finish() = 0;
};

/// Names a unit for messages: "frame 12", "rows 48..71 (tile 3 of 30)".
using UnitName = std::function<std::string(int unit)>;

/// The queue of a job of count units over the MPI world (a single process's loop when the world
/// is one rank). sink is called on rank 0 only. Rank 0 keeps the interrupt note
/// (common/interrupt_note.hpp) saying which rank holds which unit, named by name.
std::unique_ptr<WorkQueue> make_work_queue(int count, UnitSink sink, UnitName name);

}  // namespace clmarch
