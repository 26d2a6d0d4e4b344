// posix_spawn with file actions: safe in the multi-threaded test process (TBB and PoCL threads).
#include "support/child_process.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace clmarch::testing {
namespace {

/// argv for posix_spawn: the program, its arguments, a null pointer.
std::vector<char*> make_argv(std::vector<std::string>& storage) {
  std::vector<char*> argv;
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  return argv;
}

/// The current environment with the given NAME=VALUE settings added or replaced.
std::vector<std::string> merged_environment(const std::vector<std::string>& extra) {
  std::vector<std::string> out;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry(*e);
    bool replaced = false;
    for (const std::string& x : extra)
      replaced = replaced || entry.substr(0, entry.find('=') + 1) == x.substr(0, x.find('=') + 1);
    if (!replaced) out.push_back(entry);
  }
  out.insert(out.end(), extra.begin(), extra.end());
  return out;
}

pid_t spawn(const std::vector<std::string>& args, const std::vector<std::string>& environment,
            posix_spawn_file_actions_t* actions, bool sigint_ignored = false,
            const std::vector<std::string>& launcher = {}) {
  std::vector<std::string> argv_storage = launcher;
  argv_storage.push_back(CLMARCH_BINARY);
  // The shell ignores SIGINT, then becomes clmarch (same process), which inherits the disposition.
  if (sigint_ignored) argv_storage = {"/bin/sh", "-c", "trap '' INT; exec \"$0\" \"$@\"", CLMARCH_BINARY};
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<std::string> env_storage = merged_environment(environment);
  std::vector<char*> argv = make_argv(argv_storage);
  std::vector<char*> envp = make_argv(env_storage);
  // Default dispositions for the signals the tests send, even when the test runner was started
  // with them ignored (a background job of a script): clmarch keeps ignored signals ignored.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, argv_storage.front().c_str(), actions, &attributes, argv.data(), envp.data());
  posix_spawnattr_destroy(&attributes);
  if (error != 0) throw std::runtime_error(std::string("posix_spawn: ") + std::strerror(error));
  return pid;
}

int exit_code_of(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status); }

}  // namespace

ClmarchProcess::ClmarchProcess(const std::vector<std::string>& args, const std::vector<std::string>& environment,
                               bool sigint_ignored, const std::vector<std::string>& launcher) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  const std::string out = (capture_ / "out").string();
  const std::string err = (capture_ / "err").string();
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_ = spawn(args, environment, &actions, sigint_ignored, launcher);
  posix_spawn_file_actions_destroy(&actions);
  running_ = true;
}

ClmarchProcess::~ClmarchProcess() {
  if (!running_) return;
  kill(pid_, SIGKILL);
  int status = 0;
  waitpid(pid_, &status, 0);
}

bool ClmarchProcess::wait_for_stderr(const std::string& text, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (err().find(text) != std::string::npos) return true;
    if (wait(std::chrono::milliseconds(0))) return err().find(text) != std::string::npos;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

void ClmarchProcess::send_signal(int signal) {
  if (running_) kill(pid_, signal);
}

std::optional<int> ClmarchProcess::wait(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (running_) {
    int status = 0;
    const pid_t done = waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      running_ = false;
      exit_code_ = exit_code_of(status);
      break;
    }
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return exit_code_;
}

std::string ClmarchProcess::err() const { return read_text(capture_ / "err"); }

std::string ClmarchProcess::out() const { return read_text(capture_ / "out"); }

CommandResult run_clmarch_on_terminal(const std::vector<std::string>& args) {
  int master = -1;
  int slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) throw std::runtime_error("openpty failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, slave, STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, master);
  posix_spawn_file_actions_addclose(&actions, slave);
  const pid_t pid = spawn(args, {}, &actions);
  posix_spawn_file_actions_destroy(&actions);
  close(slave);
  CommandResult result;
  // Read until the child's side closes (EIO on Linux once the last slave descriptor is gone).
  for (char buffer[4096];;) {
    const ssize_t n = read(master, buffer, sizeof buffer);
    if (n > 0) {
      result.err.append(buffer, static_cast<std::size_t>(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;
    }
  }
  close(master);
  int status = 0;
  waitpid(pid, &status, 0);
  result.exit_code = exit_code_of(status);
  return result;
}

}  // namespace clmarch::testing
