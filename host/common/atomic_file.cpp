// Temporary-then-rename file writing.
#include "common/atomic_file.hpp"

#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "common/pending_file.hpp"

#include <fmt/format.h>
#include <fmt/std.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace clmarch {
namespace {

/// NAME_MAX of Linux's file systems.
constexpr std::size_t kMaxFileNameLength = 255;

}  // namespace

struct StagedFiles::Staged {
  Staged(std::filesystem::path target, std::filesystem::path temp)
      : target(std::move(target)), temp(std::move(temp)), pending(this->temp) {}
  std::filesystem::path target;
  std::filesystem::path temp;
  PendingFile pending;
};

StagedFiles::StagedFiles() = default;

StagedFiles::~StagedFiles() {
  for (const auto& staged : staged_) {
    std::error_code ignored;
    std::filesystem::remove(staged->temp, ignored);
  }
}

void StagedFiles::stage(const std::filesystem::path& target,
                        const std::function<void(const std::filesystem::path& temp)>& write) {
  if (staged_.size() >= static_cast<std::size_t>(kMaxPendingFiles)) {
    throw std::logic_error("StagedFiles: more files than the signal handler can remove");
  }
  // The temporary name adds a dot and ".clmarch-PID" to the target's; the stem is cut so that it
  // stays within the folder's name limit when the target's own name is near it.
  const std::string tag = fmt::format(".clmarch-{}{}", getpid(), target.extension().string());
  std::string stem = target.stem().string();
  stem.resize(std::min(stem.size(), kMaxFileNameLength - std::min(kMaxFileNameLength, tag.size() + 1)));
  std::filesystem::path temp = target;
  temp.replace_filename("." + stem + tag);
  // Registered before the file exists, so that no signal finds it unknown.
  staged_.push_back(std::make_unique<Staged>(target, temp));
  try {
    write(temp);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    staged_.pop_back();
    throw;
  }
}

void StagedFiles::commit() {
  // A Ctrl-C during the writes leaves no new file: the temporary ones go, the targets stay as they were.
  throw_if_cancelled();
  // A rename in the target's own folder fails only if the folder changed since the checks before
  // the render. The likely change, a target that became a folder, is caught before anything is
  // renamed; anything rarer (the folder made read-only, a bind mount on a target) fails that
  // rename alone and leaves the files renamed before it.
  for (const auto& staged : staged_) {
    std::error_code error;
    if (std::filesystem::is_directory(staged->target, error)) {
      throw OutputError(fmt::format("{}: cannot write: is a folder", staged->target.string()));
    }
  }
  while (!staged_.empty()) {
    const Staged& next = *staged_.front();
    std::error_code error;
    std::filesystem::rename(next.temp, next.target, error);
    if (error) throw OutputError(fmt::format("{}: cannot write: {}", next.target.string(), error.message()));
    staged_.erase(staged_.begin());
  }
}

void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& temp)>& write) {
  StagedFiles files;
  files.stage(target, write);
  files.commit();
}

void write_bytes(const std::filesystem::path& file, const void* data, std::size_t size,
                 const std::filesystem::path& target) {
  const auto fail = [&](int error) {
    return OutputError(fmt::format("{}: cannot write: {}", target.string(), std::strerror(error)));
  };
  const int fd = open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw fail(errno);
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = write(fd, bytes, size);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      const int error = written < 0 ? errno : EIO;
      close(fd);
      throw fail(error);
    }
    bytes += written;
    size -= static_cast<std::size_t>(written);
  }
  if (close(fd) != 0) throw fail(errno);
}

void write_file_atomically(const std::filesystem::path& path, const std::string& text) {
  write_atomically(path, [&](const std::filesystem::path& temp) { write_bytes(temp, text.data(), text.size(), path); });
}

bool is_special_file(const std::filesystem::path& path) {
  std::error_code error;
  const std::filesystem::file_type type = std::filesystem::status(path, error).type();
  return type == std::filesystem::file_type::character || type == std::filesystem::file_type::block ||
         type == std::filesystem::file_type::fifo || type == std::filesystem::file_type::socket;
}

void check_output_name(const std::filesystem::path& path, const std::string& option) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(fmt::format("{} {}: is a folder, expected a file name", option, path.string()));
  }
  if (is_special_file(path)) {
    throw InputError(
        fmt::format("{} {}: is a device, pipe or socket, expected a file name (outputs are written "
                    "beside their file and renamed over it)",
                    option, path.string()));
  }
  if (path.filename().native().size() > kMaxFileNameLength) {
    throw InputError(fmt::format("{} {}: the file name has {} characters, more than the {} a folder takes", option,
                                 path.string(), path.filename().native().size(), kMaxFileNameLength));
  }
}

void check_output_folder(const std::filesystem::path& path, const std::string& option) {
  std::filesystem::path folder = path.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) {
    throw InputError(fmt::format("{} {}: folder {} does not exist", option, path.string(), folder.string()));
  }
  // Before the folder's own checks: /dev/null's folder is not writable to most users, which would
  // hide what is really wrong.
  check_output_name(path, option);
  if (access(folder.c_str(), W_OK) != 0) {
    throw InputError(fmt::format("{} {}: folder {} is not writable", option, path.string(), folder.string()));
  }
  // access() says yes to root everywhere, and to anyone on /proc or a read-only mount: creating
  // a file is the only test that a render's result will find a place.
  const std::filesystem::path probe = folder / fmt::format(".clmarch-probe-{}", getpid());
  const int fd = open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0 && errno != EEXIST) {
    throw InputError(fmt::format("{} {}: cannot create files in folder {}: {}", option, path.string(), folder.string(),
                                 std::strerror(errno)));
  }
  if (fd >= 0) {
    close(fd);
    unlink(probe.c_str());
  }
}

}  // namespace clmarch
