// `clmarch devices`: the OpenCL platforms and devices, numbered for --device.
#pragma once

#include <CLI/CLI.hpp>

namespace clmarch {

CLI::App* add_devices_command(CLI::App& app);
int run_devices_command();

}  // namespace clmarch
