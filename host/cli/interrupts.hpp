// Ctrl-C and SIGTERM: the first one asks the work to stop at its next cancellation point (the CLI
// then exits 128 + signal, writing nothing); a second one exits at once.
#pragma once

namespace clmarch {

/// Installs the SIGINT and SIGTERM handlers (except for a signal the parent process ignores). The
/// first signal sets cancellation_requested(); a second removes the temporary output file being
/// written, if any, and _exits 128 + the first signal. Also ignores SIGXFSZ, so that a write past
/// the file size limit fails with EFBIG and is reported (exit code 4, no file) instead of killing
/// the process with its temporary file left behind.
void install_interrupt_handlers();

/// 128 + the number of the first signal received: 130 for SIGINT, 143 for SIGTERM; 130 when none
/// was (cancellation requested in-process).
int interrupted_exit_code();

}  // namespace clmarch
