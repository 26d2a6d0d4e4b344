// MPI start-up and the rank's identity. Without CLMARCH_HAVE_MPI every process is rank 0 of 1.
#include "distributed/mpi_world.hpp"

#include <fmt/format.h>

#include <cstdlib>

#include <unistd.h>

#if CLMARCH_HAVE_MPI
#include <mpi.h>
#endif

namespace clmarch {
namespace {

MpiWorld g_world;
#if CLMARCH_HAVE_MPI
bool g_started = false;
#endif

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) != 0) return "unknown host";
  return name;
}

}  // namespace

bool launched_as_ranks() {
#if CLMARCH_HAVE_MPI
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_STEP_NUM_TASKS"}) {
    const char* value = std::getenv(variable);
    if (value && std::atoi(value) > 1) return true;
  }
#endif
  return false;
}

void start_mpi_if_launched() {
  g_world.host = host_name();
#if CLMARCH_HAVE_MPI
  if (!launched_as_ranks()) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
  if (provided < MPI_THREAD_SERIALIZED) {
    MPI_Abort(MPI_COMM_WORLD, 70);
  }
  g_started = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_world.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_world.size);
  // The ranks sharing this node's memory, in rank order: the MPI-3 split that srun and mpirun both
  // support (OMPI_COMM_WORLD_LOCAL_RANK is Open MPI's alone).
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, g_world.rank, MPI_INFO_NULL, &node);
  MPI_Comm_rank(node, &g_world.local_rank);
  MPI_Comm_free(&node);
#endif
}

const MpiWorld& mpi_world() { return g_world; }

void finish_mpi() {
#if CLMARCH_HAVE_MPI
  if (!g_started) return;
  g_started = false;
  const std::lock_guard lock(mpi_mutex());
  MPI_Finalize();
#endif
}

void abort_mpi(int exit_code) {
#if CLMARCH_HAVE_MPI
  if (!g_started) return;
  MPI_Abort(MPI_COMM_WORLD, exit_code);
#else
  (void)exit_code;
#endif
}

std::mutex& mpi_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::string rank_label(int rank, const std::string& host) { return fmt::format("rank {} on {}", rank, host); }

}  // namespace clmarch
