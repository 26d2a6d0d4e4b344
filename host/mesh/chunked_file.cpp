// ChunkedFile: a std::streambuf over a file descriptor with checked writes.
#include "mesh/chunked_file.hpp"

#include "common/cancellation.hpp"
#include "common/errors.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

namespace clmarch {

ChunkedFile::ChunkedFile(const std::filesystem::path& file, std::filesystem::path target)
    : target_(std::move(target)), buffer_(kChunkBytes) {
  fd_ = open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) {
    error_ = errno;
    fail();
  }
  setp(buffer_.data(), buffer_.data() + buffer_.size());
}

ChunkedFile::~ChunkedFile() {
  if (fd_ >= 0) ::close(fd_);
}

void ChunkedFile::append(const void* data, std::size_t size) {
  const auto wanted = static_cast<std::streamsize>(size);
  if (sputn(static_cast<const char*>(data), wanted) != wanted) fail();
}

void ChunkedFile::close() {
  const bool flushed = flush_buffer();
  const int closed = ::close(fd_);
  fd_ = -1;
  if (flushed && closed != 0) error_ = errno;
  if (error_ != 0) fail();
}

ChunkedFile::int_type ChunkedFile::overflow(int_type c) {
  if (!flush_buffer()) return traits_type::eof();
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
  }
  return traits_type::not_eof(c);
}

int ChunkedFile::sync() { return flush_buffer() ? 0 : -1; }

bool ChunkedFile::flush_buffer() {
  if (error_ != 0) return false;
  // A full buffer is the unit of work between two looks at Ctrl-C: a mesh of gigabytes stops
  // within a chunk instead of after the whole file.
  throw_if_cancelled();
  const char* bytes = pbase();
  std::size_t size = static_cast<std::size_t>(pptr() - pbase());
  while (size > 0) {
    const ssize_t written = write(fd_, bytes, size);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      error_ = written < 0 ? errno : EIO;
      return false;
    }
    bytes += written;
    size -= static_cast<std::size_t>(written);
  }
  setp(buffer_.data(), buffer_.data() + buffer_.size());
  return true;
}

void ChunkedFile::fail() const {
  throw OutputError(fmt::format("{}: cannot write: {}", target_.string(), std::strerror(error_)));
}

}  // namespace clmarch
