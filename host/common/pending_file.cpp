// Fixed buffers and lock-free flags: the signal handler may only read plain memory and unlink().
// Slots are taken and released by the thread that writes the outputs; the handler only reads.
#include "common/pending_file.hpp"

#include <atomic>
#include <climits>
#include <cstring>

#include <unistd.h>

namespace clmarch {
namespace {

struct Slot {
  char path[PATH_MAX];
  std::atomic<bool> registered{false};
};
Slot g_slots[kMaxPendingFiles];
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler reads these flags");

}  // namespace

PendingFile::PendingFile(const std::filesystem::path& path) {
  const std::string& text = path.native();
  if (text.size() >= PATH_MAX) return;
  for (int i = 0; i < kMaxPendingFiles; ++i) {
    Slot& slot = g_slots[i];
    if (slot.registered.load()) continue;
    // The flag is down while the buffer changes, so the handler never reads a half-copied name.
    std::memcpy(slot.path, text.c_str(), text.size() + 1);
    slot.registered.store(true, std::memory_order_seq_cst);
    slot_ = i;
    return;
  }
}

PendingFile::~PendingFile() {
  if (slot_ >= 0) g_slots[slot_].registered.store(false, std::memory_order_seq_cst);
}

void remove_pending_files_in_signal_handler() {
  for (Slot& slot : g_slots) {
    if (slot.registered.load(std::memory_order_seq_cst)) unlink(slot.path);
  }
}

}  // namespace clmarch
