// A fixed buffer and a lock-free flag: the signal handler may only read plain memory and unlink().
#include "common/pending_file.hpp"

#include <atomic>
#include <climits>
#include <cstring>

#include <unistd.h>

namespace clmarch {
namespace {

char g_path[PATH_MAX];
std::atomic<bool> g_registered{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler reads this flag");

}  // namespace

PendingFile::PendingFile(const std::filesystem::path& path) {
  const std::string& text = path.native();
  if (text.size() >= sizeof(g_path)) return;
  // The flag is down while the buffer changes, so the handler never reads a half-copied name.
  g_registered.store(false, std::memory_order_seq_cst);
  std::memcpy(g_path, text.c_str(), text.size() + 1);
  g_registered.store(true, std::memory_order_seq_cst);
  registered_ = true;
}

PendingFile::~PendingFile() {
  if (registered_) g_registered.store(false, std::memory_order_seq_cst);
}

void remove_pending_file_in_signal_handler() {
  if (g_registered.load(std::memory_order_seq_cst)) unlink(g_path);
}

}  // namespace clmarch
