// An output file written a chunk at a time, every write checked: meshes of tens of millions of
// triangles are never held as one string.
#pragma once

#include <cstddef>
#include <filesystem>
#include <streambuf>
#include <vector>

namespace clmarch {

/// A file written through a buffer of kChunkBytes with write(2), each call checked (a full disk, a
/// file size limit): std::ofstream loses the error of its last buffer's flush. A std::streambuf,
/// so that a library writing to a std::ostream (tinygltf) goes through it too. Messages name
/// target, the file the user asked for, not the temporary file written.
class ChunkedFile : public std::streambuf {
 public:
  /// The buffer's size: large enough that a write(2) call costs nothing beside its data.
  static constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

  /// Creates or truncates file; throws OutputError if it cannot.
  ChunkedFile(const std::filesystem::path& file, std::filesystem::path target);
  /// Closes the file if close() was not reached (an exception is on its way).
  ~ChunkedFile() override;
  ChunkedFile(const ChunkedFile&) = delete;
  ChunkedFile& operator=(const ChunkedFile&) = delete;

  /// Appends size bytes; throws OutputError once a write has failed, Cancelled after a Ctrl-C.
  void append(const void* data, std::size_t size);
  /// Writes what is buffered and closes the file; throws OutputError if any write or the close
  /// failed (also those of a std::ostream over this buffer, which only set its badbit).
  void close();
  /// The file the user asked for, which messages name.
  const std::filesystem::path& target() const { return target_; }

 protected:
  int_type overflow(int_type c) override;
  int sync() override;

 private:
  /// Writes the buffered bytes; false, with error_ set, if a write failed.
  bool flush_buffer();
  /// The OutputError of error_.
  [[noreturn]] void fail() const;

  std::filesystem::path target_;
  int fd_ = -1;
  int error_ = 0;
  std::vector<char> buffer_;
};

}  // namespace clmarch
