// The one place where errors become a message on stderr and an exit code (docs/cli.md).
#pragma once

#include <functional>

namespace clmarch {

/// Runs command and returns its exit code; an exception becomes one line on stderr (a build log
/// may follow a device error) and its exit code: InputError 2, DeviceError and cl::Error 3,
/// OutputError 4, Cancelled 128 + signal, any other exception kExitInternalError.
int run_reporting_errors(const std::function<int()>& command);

}  // namespace clmarch
