// Output files appear whole or not at all: written to a temporary name beside the target, then
// renamed over it.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace clmarch {

/// Calls write(temp_path) with a temporary path in the target's folder that keeps the target's
/// extension, then renames it to target. On any exception the temporary file is removed and the
/// exception propagates. When cancellation was requested during the write, it throws Cancelled
/// instead of renaming; a second signal, which exits at once, removes the temporary file too.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& temp)>& write);

/// Writes size bytes to file with write(2), checking every call and the close (a file size limit,
/// a full disk): stdio and the libraries writing through it lose the error of the last buffer's
/// flush. Throws OutputError naming target, the file the user asked for.
void write_bytes(const std::filesystem::path& file, const void* data, std::size_t size,
                 const std::filesystem::path& target);

/// Writes text to path atomically. Throws OutputError on failure.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

/// Fails with InputError (naming option) unless path's folder exists and a file can be created in
/// it (tried with a probe file, removed at once); checked before a render starts so that a bad
/// path costs nothing.
void check_output_folder(const std::filesystem::path& path, const std::string& option);

/// Fails with InputError (naming option) if path is a folder or its file name is longer than a
/// folder takes; part of check_output_folder, and alone for the numbered files of a sequence,
/// whose folder is the same for every frame.
void check_output_name(const std::filesystem::path& path, const std::string& option);

}  // namespace clmarch
