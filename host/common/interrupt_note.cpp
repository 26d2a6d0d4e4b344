// Two fixed buffers: the setter fills the one the handler is not reading, then publishes it.
#include "common/interrupt_note.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>

#include <unistd.h>

namespace clmarch {
namespace {

constexpr std::size_t kNoteCapacity = 4096;
struct Note {
  char text[kNoteCapacity];
  std::size_t length = 0;
};
Note g_notes[2];
/// The published buffer, or -1 for no note.
std::atomic<int> g_current{-1};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the index");

}  // namespace

void set_interrupt_note(std::string_view note) {
  if (note.empty()) {
    g_current.store(-1);
    return;
  }
  const int next = g_current.load() == 0 ? 1 : 0;
  Note& n = g_notes[next];
  constexpr std::string_view kPrefix = "clmarch: ";
  const std::size_t length = std::min(note.size(), kNoteCapacity - kPrefix.size() - 1);
  std::memcpy(n.text, kPrefix.data(), kPrefix.size());
  std::memcpy(n.text + kPrefix.size(), note.data(), length);
  n.text[kPrefix.size() + length] = '\n';
  n.length = kPrefix.size() + length + 1;
  g_current.store(next);
}

void write_interrupt_note() {
  const int current = g_current.load();
  if (current < 0) return;
  const Note& n = g_notes[current];
  [[maybe_unused]] const ssize_t written = write(STDERR_FILENO, n.text, n.length);
}

}  // namespace clmarch
