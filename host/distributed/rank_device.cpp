// Device choice per rank, and gathering every rank's lines on rank 0.
#include "distributed/rank_device.hpp"

#include "distributed/mpi_world.hpp"

#if CLMARCH_HAVE_MPI
#include <mpi.h>
#endif

namespace clmarch {

std::optional<int> rank_default_device(const std::vector<DeviceEntry>& devices, int local_rank) {
  std::vector<int> gpus;
  for (const DeviceEntry& d : devices) {
    if (d.is_gpu) gpus.push_back(d.index);
  }
  if (gpus.empty()) return std::nullopt;
  return gpus[static_cast<std::size_t>(local_rank) % gpus.size()];
}

std::vector<std::string> gather_on_rank0(const std::string& text) {
  const MpiWorld& world = mpi_world();
  if (!world.distributed()) return {text};
#if CLMARCH_HAVE_MPI
  const std::lock_guard lock(mpi_mutex());
  int length = static_cast<int>(text.size());
  std::vector<int> lengths(static_cast<std::size_t>(world.size));
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<int> offsets(lengths.size(), 0);
  std::string all;
  if (world.rank == 0) {
    int total = 0;
    for (std::size_t i = 0; i < lengths.size(); ++i) {
      offsets[i] = total;
      total += lengths[i];
    }
    all.resize(static_cast<std::size_t>(total));
  }
  MPI_Gatherv(text.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
  std::vector<std::string> texts;
  if (world.rank == 0) {
    for (std::size_t i = 0; i < lengths.size(); ++i) {
      texts.push_back(all.substr(static_cast<std::size_t>(offsets[i]), static_cast<std::size_t>(lengths[i])));
    }
  }
  return texts;
#else
  return {text};
#endif
}

}  // namespace clmarch
