// The temporary files of atomic writes, known to the signal handler so that a Ctrl-C that exits
// at once still removes them.
#pragma once

#include <filesystem>

namespace clmarch {

/// Registers path as a temporary file for its lifetime. Up to kMaxPendingFiles at once (the files
/// of one render, written before any is renamed into place); paths longer than PATH_MAX, or past
/// that many, are not registered.
inline constexpr int kMaxPendingFiles = 4;

class PendingFile {
 public:
  explicit PendingFile(const std::filesystem::path& path);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

 private:
  int slot_ = -1;
};

/// Unlinks the registered files, if any. Async-signal-safe: only for the signal handler.
void remove_pending_files_in_signal_handler();

}  // namespace clmarch
