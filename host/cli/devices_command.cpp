// `clmarch devices`.
#include "cli/devices_command.hpp"

#include "cl/devices.hpp"
#include "common/errors.hpp"

#include <fmt/format.h>

namespace clmarch {

CLI::App* add_devices_command(CLI::App& app) {
  return app.add_subcommand("devices", "List OpenCL platforms and devices with the index --device takes");
}

int run_devices_command() {
  const std::vector<DeviceEntry> devices = list_devices();
  if (devices.empty()) throw DeviceError(no_device_message());
  std::optional<int> chosen;
  try {
    chosen = select_device(std::nullopt).index;
  } catch (const DeviceError&) {
  }
  for (const DeviceEntry& d : devices) {
    const char* type = d.is_gpu ? "GPU" : d.is_cpu ? "CPU" : "other";
    fmt::print("{}: {} [{}] on {}{}\n", d.index, d.name, type, d.platform_name, chosen == d.index ? "  (default)" : "");
  }
  return kExitOk;
}

}  // namespace clmarch
