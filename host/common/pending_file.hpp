// The temporary file an atomic write is filling, known to the signal handler so that a second
// Ctrl-C, which exits at once, still removes it.
#pragma once

#include <filesystem>

namespace clmarch {

/// Registers path as the file being written for its lifetime; one at a time (writes are sequential).
/// Paths longer than PATH_MAX are not registered.
class PendingFile {
 public:
  explicit PendingFile(const std::filesystem::path& path);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

 private:
  bool registered_ = false;
};

/// Unlinks the registered file, if any. Async-signal-safe: only for the signal handler.
void remove_pending_file_in_signal_handler();

}  // namespace clmarch
