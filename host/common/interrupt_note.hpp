// A line the Ctrl-C and SIGTERM handling prints after "clmarch: interrupted": what was in
// progress when the process was stopped (rank 0 of an MPI job: which rank held which frame or
// tile, for a job that mpirun ends because a rank died).
#pragma once

#include <string_view>

namespace clmarch {

/// Sets the note (empty: none); longer notes are cut at 4000 characters. Not for signal handlers;
/// callers serialise their calls.
void set_interrupt_note(std::string_view note);

/// Writes "clmarch: NOTE\n" to stderr if a note is set. Async-signal-safe (write(2) of a buffer
/// published by an atomic index).
void write_interrupt_note();

}  // namespace clmarch
