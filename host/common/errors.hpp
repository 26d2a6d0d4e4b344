// The error kinds that reach the user, each with its exit code (docs/cli.md).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace clmarch {

/// Process exit codes.
enum ExitCode : int {
  kExitOk = 0,
  /// `clmarch check`: the renders disagree beyond the tolerances.
  kExitCheckFailed = 1,
  /// Bad scene file, option or output path.
  kExitBadInput = 2,
  /// An OpenCL platform, device, build or launch failed.
  kExitDeviceFault = 3,
  /// Writing an output file failed.
  kExitOutputFailed = 4,
  /// A bug: an exception no other code covers (sysexits' EX_SOFTWARE).
  kExitInternalError = 70,
  /// Interrupted by SIGINT (Ctrl-C); SIGTERM gives 128 + 15 = 143.
  kExitInterrupted = 130,
};

/// text with its control characters written as escapes (\n, \r, \0, \x1b): a message that quotes
/// a user's value (a file name with a newline, a NUL in a scene) stays one line and is not cut short.
std::string one_line(std::string_view text);

/// Bad input from the user; the message is one line naming the file or option, what and why.
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::string_view message) : std::runtime_error(one_line(message)) {}
};

/// An OpenCL failure; the message names the device and the failing call (and may carry a build log).
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Writing a result failed (disk full, permissions changed under us); one line, as InputError.
class OutputError : public std::runtime_error {
 public:
  explicit OutputError(std::string_view message) : std::runtime_error(one_line(message)) {}
};

/// A failure that ends the command with exit_code: a rank of a distributed render whose unit
/// failed (its error was printed with the rank, host and unit), or rank 0 saying which rank
/// failed. An empty message prints nothing more.
class RankFailure : public std::runtime_error {
 public:
  RankFailure(int exit_code, std::string_view message)
      : std::runtime_error(std::string(message)), exit_code(exit_code) {}
  int exit_code;
};

}  // namespace clmarch
