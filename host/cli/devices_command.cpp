// `clmarch devices`; under MPI, every rank's devices, printed by rank 0 in rank order.
#include "cli/devices_command.hpp"

#include "cl/devices.hpp"
#include "common/errors.hpp"
#include "distributed/mpi_world.hpp"
#include "distributed/rank_device.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace clmarch {
namespace {

/// The listing of this process's devices, the default marked; empty when there are none.
std::string device_lines(const std::vector<DeviceEntry>& devices, std::optional<int> chosen,
                         const std::string& indent) {
  std::string lines;
  for (const DeviceEntry& d : devices) {
    const char* type = d.is_gpu ? "GPU" : d.is_cpu ? "CPU" : "other";
    lines += fmt::format("{}{}: {} [{}] on {}{}\n", indent, d.index, d.name, type, d.platform_name,
                         chosen == d.index ? "  (default)" : "");
  }
  return lines;
}

}  // namespace

CLI::App* add_devices_command(CLI::App& app) {
  return app.add_subcommand("devices", "List OpenCL platforms and devices with the index --device takes");
}

int run_devices_command() {
  const std::vector<DeviceEntry> devices = list_devices();
  const MpiWorld& world = mpi_world();
  if (!world.distributed()) {
    if (devices.empty()) throw DeviceError(no_device_message());
    std::optional<int> chosen;
    try {
      chosen = select_device(std::nullopt).index;
    } catch (const DeviceError&) {
    }
    std::fputs(device_lines(devices, chosen, "").c_str(), stdout);
    return kExitOk;
  }
  // Every rank takes part in the gathering, a rank without devices too (it says so).
  std::optional<int> chosen = rank_default_device(devices, world.local_rank);
  if (!chosen && !devices.empty()) chosen = select_device(std::nullopt).index;
  const std::string lines = devices.empty() ? "  " + no_device_message() + "\n" : device_lines(devices, chosen, "  ");
  const std::string text =
      fmt::format("{} (local rank {}):\n{}", rank_label(world.rank, world.host), world.local_rank, lines);
  const std::vector<std::string> texts = gather_on_rank0(fmt::format("{}{}", devices.empty() ? 'x' : ' ', text));
  bool all_have_devices = true;
  for (const std::string& t : texts) {
    std::fputs(t.substr(1).c_str(), stdout);
    all_have_devices = all_have_devices && t.front() != 'x';
  }
  if (world.rank == 0 && !all_have_devices) return kExitDeviceFault;
  return devices.empty() ? kExitDeviceFault : kExitOk;
}

}  // namespace clmarch
