#include "signals.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace raycast::io {
namespace {

char g_pending[pending_path_capacity];
std::atomic<bool> g_has_pending{false};

constexpr int handled[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void on_fatal_signal(int sig) {
  if (g_has_pending.load()) unlink(g_pending);
  std::signal(sig, SIG_DFL);
  raise(sig);
}

}  // namespace

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_fatal_signal;
  sigemptyset(&sa.sa_mask);
  for (const int sig : handled) sigaction(sig, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);
}

void reserve_standard_streams() noexcept {
  for (int fd = 0; fd <= 2; ++fd) {
    if (fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    const int null_fd = open("/dev/null", O_RDONLY);  // the lowest free number: fd
    if (null_fd >= 0 && null_fd != fd) {
      dup2(null_fd, fd);
      close(null_fd);
    }
  }
}

fatal_signals_blocked::fatal_signals_blocked() noexcept {
  sigset_t block;
  sigemptyset(&block);
  for (const int sig : handled) sigaddset(&block, sig);
  sigprocmask(SIG_BLOCK, &block, &old_);
}

fatal_signals_blocked::~fatal_signals_blocked() { sigprocmask(SIG_SETMASK, &old_, nullptr); }

bool register_pending_temporary(const char* path) noexcept {
  const size_t n = std::strlen(path) + 1;
  if (n > sizeof g_pending) return false;
  const fatal_signals_blocked blocked;
  std::memcpy(g_pending, path, n);
  g_has_pending.store(true);
  return true;
}

void forget_pending_temporary() noexcept { g_has_pending.store(false); }

}  // namespace raycast::io
