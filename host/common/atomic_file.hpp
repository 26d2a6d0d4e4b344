// Output files appear whole or not at all: written to a temporary name beside the target, then
// renamed over it.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace clmarch {

/// Files written together (an image and its buffers): each is written to a temporary file beside
/// its target when staged, and commit() renames them all into place, so that a failure or a
/// Ctrl-C while writing any of them leaves every target as it was. Temporary files that were not
/// committed are removed (also by a signal that exits at once: common/pending_file.hpp).
class StagedFiles {
 public:
  StagedFiles();
  ~StagedFiles();
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;

  /// Calls write(temp_path) with a temporary path in target's folder that keeps target's
  /// extension. On an exception the temporary file is removed and the exception propagates.
  /// At most kMaxPendingFiles files.
  void stage(const std::filesystem::path& target, const std::function<void(const std::filesystem::path& temp)>& write);
  /// Renames the staged files to their targets; throws Cancelled instead if cancellation was
  /// requested (nothing renamed), OutputError if a target is a folder (nothing renamed) or a
  /// rename fails (the files renamed before it stay).
  void commit();

 private:
  struct Staged;
  std::vector<std::unique_ptr<Staged>> staged_;
};

/// One file through StagedFiles: written to a temporary file, then renamed over target.
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

/// Fails with InputError (naming option) if path is a folder, a device, pipe or socket (the file
/// written beside it would be renamed over it), or its file name is longer than a folder takes;
/// part of check_output_folder, and alone for the numbered files of a sequence, whose folder is
/// the same for every frame.
void check_output_name(const std::filesystem::path& path, const std::string& option);

/// Whether path is a device, pipe or socket (/dev/null, /dev/stdout), not a file to write over.
bool is_special_file(const std::filesystem::path& path);

}  // namespace clmarch
