// Messages on stderr besides errors: the normal "clmarch: wrote ..." lines, the --verbose details,
// and nothing at all with --quiet. One setting for the whole process, chosen by the CLI.
#pragma once

#include <functional>
#include <string_view>

namespace clmarch {

/// How much the program says on stderr; errors are printed whatever it is.
enum class Verbosity { Quiet, Normal, Verbose };

/// The process-wide setting (default Normal); set once by the CLI before any work starts.
void set_verbosity(Verbosity verbosity);
Verbosity verbosity();

/// Where a library's caller takes the lines instead of stderr (the Python module hands them to
/// Python's logging and warnings): called with the level and the line without "clmarch: ", from
/// any thread. Verbosity still decides which lines are made.
enum class LogLevel { Info, Verbose, Warning };
using LogSink = std::function<void(LogLevel level, std::string_view line)>;
/// Sends the lines to sink from now on; an empty sink restores stderr.
void set_log_sink(LogSink sink);

/// "clmarch: " + line on stderr unless --quiet (results: the files written).
void log_info(std::string_view line);
/// "clmarch: " + line on stderr with --verbose only (device, build, dispatch details).
void log_verbose(std::string_view line);
/// "clmarch: warning: " + line on stderr unless --quiet, once per process for each line (the
/// frames of a sequence load the scene again and again).
void log_warning(std::string_view line);

}  // namespace clmarch
