// The MPI job this process is one rank of, if any: started under mpirun (or srun) with more than
// one rank, clmarch splits its work among them (docs/cli.md#mpi); otherwise it is one process and
// never initialises MPI.
#pragma once

#include <mutex>
#include <string>

namespace clmarch {

/// Where this process stands in the job; size 1 for a plain run.
struct MpiWorld {
  int rank = 0;
  int size = 1;
  /// The rank's index among the ranks on its own node (picks its GPU).
  int local_rank = 0;
  /// The node's name, for messages.
  std::string host;

  bool distributed() const { return size > 1; }
};

/// Whether the launcher's environment says this process is one of several ranks
/// (Open MPI's OMPI_COMM_WORLD_SIZE, PMI's PMI_SIZE or srun's SLURM_STEP_NUM_TASKS above 1), read
/// before MPI is initialised so that a plain run never starts it. Always false without MPI built
/// in. A failed MPI call ends the job (MPI's default error handler).
bool launched_as_ranks();

/// Initialises MPI (threads serialised: every call holds mpi_mutex()) when launched_as_ranks(),
/// and fills mpi_world(). Call once, before any other function here.
void start_mpi_if_launched();

/// This process's place in the job (rank 0 of 1 until start_mpi_if_launched found several).
const MpiWorld& mpi_world();

/// Finalises MPI if it was started; every rank calls it before exiting.
void finish_mpi();
/// Ends every rank of the job with exit_code (MPI_Abort) when MPI was started: for an error that
/// leaves other ranks waiting on this one. Returns only without MPI.
void abort_mpi(int exit_code);

/// Held around every MPI call: the library was initialised for serialised threads (rank 0's
/// coordinator thread and its rendering main thread both call it).
std::mutex& mpi_mutex();

/// "rank R on HOST", for messages.
std::string rank_label(int rank, const std::string& host);

}  // namespace clmarch
