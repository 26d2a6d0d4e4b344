// Ctrl-C and SIGTERM: the first one asks the work to stop at its next cancellation point (the CLI
// then exits 128 + signal, writing nothing), or exits at once inside a BlockingCall; a second one
// exits at once.
#pragma once

#include <string_view>

namespace clmarch {

/// Installs the SIGINT and SIGTERM handlers (a signal the parent process ignores stays ignored,
/// and is blocked so that no library's handler sees it either). The first signal sets
/// cancellation_requested(), and inside a BlockingCall prints "clmarch: interrupted" and _exits
/// 128 + signal; a second removes the temporary output files being written, if any, and _exits
/// 128 + the first signal. Also ignores SIGXFSZ, so that a write past the file size limit fails
/// with EFBIG and is reported (exit code 4, no file) instead of killing the process with its
/// temporary file left behind.
void install_interrupt_handlers();

/// Makes the first signal end the process at once, as a second one does (removing the temporary
/// files being written), after writing message (one line, e.g. "clmarch: rank 1 on node7:
/// interrupted") and the interrupt note. For the ranks of an MPI job: mpirun turns Ctrl-C, or a
/// lost rank, into SIGTERM for every rank and SIGKILLs those still running a moment later, which
/// would leave the temporary file of a rank still writing.
void exit_at_first_signal(std::string_view message);

/// 128 + the number of the first signal received: 130 for SIGINT, 143 for SIGTERM; 130 when none
/// was (cancellation requested in-process).
int interrupted_exit_code();

}  // namespace clmarch
