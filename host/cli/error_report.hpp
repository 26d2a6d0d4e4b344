// The one place where errors become a message on stderr and an exit code (docs/cli.md).
#pragma once

#include <functional>
#include <string>

namespace clmarch {

/// Runs command and returns its exit code; an exception becomes one line on stderr (a build log
/// may follow a device error) and its exit code: InputError 2, DeviceError and cl::Error 3,
/// OutputError 4, Cancelled 128 + signal, any other exception kExitInternalError.
int run_reporting_errors(const std::function<int()>& command);

/// Where the work that may fail runs, put at the front of every error message until cleared
/// (empty): "rank 1 on node7, frame 12" makes "clmarch: rank 1 on node7, frame 12: MESSAGE".
void set_error_context(std::string context);
/// The context set last.
const std::string& error_context();

}  // namespace clmarch
