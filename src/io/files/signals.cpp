#include "io/files/signals.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>

namespace raycast::io {
namespace {

char g_pending[pending_path_capacity];
std::atomic<bool> g_has_pending{false};

// The failure a crash is reported as, while armed (crash_means_failure).
char g_crash_what[1024];
std::atomic<bool> g_crash_armed{false};
char g_subject[1024] = "raycast";

// Default action "terminate" (as SIGRTMIN..SIGRTMAX, handled in a loop).
constexpr int terminating[] = {SIGHUP,  SIGINT,    SIGQUIT, SIGTERM, SIGUSR1, SIGUSR2, SIGALRM,
                               SIGVTALRM, SIGPROF, SIGXCPU, SIGIO,   SIGPWR,  SIGSTKFLT};
// Crashes: the faulting instruction, or abort().
constexpr int crashes[] = {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGSYS, SIGTRAP};

struct sigaction g_previous[NSIG];

// Where reports go: standard error, or its saved copy while silenced.
std::atomic<int> g_report_fd{STDERR_FILENO};

void remove_pending() noexcept {
  if (g_has_pending.load()) unlink(g_pending);
}

void write_stderr(const char* s) noexcept {
  size_t n = std::strlen(s);
  while (n > 0) {
    const ssize_t w = write(g_report_fd.load(), s, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return;
    s += w;
    n -= size_t(w);
  }
}

// `in` with control characters as \xNN, cut to fit: one line. Async-signal-safe.
void escape_into(char* out, size_t cap, const char* in) noexcept {
  static constexpr char hex[] = "0123456789abcdef";
  size_t o = 0;
  for (; *in && o + 5 < cap; ++in) {
    const unsigned char c = static_cast<unsigned char>(*in);
    if (c < 0x20 || c == 0x7f) {
      out[o++] = '\\';
      out[o++] = 'x';
      out[o++] = hex[c >> 4];
      out[o++] = hex[c & 15];
    } else {
      out[o++] = char(c);
    }
  }
  out[o] = '\0';
}

// "raycast: error: <what> (<cause>)" (or "<what>: <cause>"), then exit 1: from a signal handler
// as well (write() and _exit() only).
[[noreturn]] void report(const char* what, const char* cause, bool parenthesized) noexcept {
  char c[512];
  escape_into(c, sizeof c, cause);
  write_stderr("raycast: error: ");
  write_stderr(what);
  write_stderr(parenthesized ? " (" : ": ");
  write_stderr(c);
  write_stderr(parenthesized ? ")\n" : "\n");
  _exit(1);
}
[[noreturn]] void report_crash(const char* cause) noexcept { report(g_crash_what, cause, true); }

const char* crash_name(int sig) {
  switch (sig) {
    case SIGSEGV: return "Segmentation fault";
    case SIGBUS: return "Bus error";
    case SIGILL: return "Illegal instruction";
    case SIGFPE: return "Floating point exception";
    case SIGABRT: return "Aborted";
    case SIGSYS: return "Bad system call";
    case SIGTRAP: return "Trace/breakpoint trap";
  }
  return "crashed";
}

extern "C" void on_fatal_signal(int sig) {
  remove_pending();
  std::signal(sig, SIG_DFL);
  raise(sig);  // delivered, with the default action, when the handler returns
}

extern "C" void on_crash(int sig, siginfo_t* info, void*) {
  remove_pending();
  if (g_crash_armed.load()) report_crash(crash_name(sig));
  // Back to the previous action: a faulting instruction faults again; a sent signal is resent.
  sigaction(sig, &g_previous[sig], nullptr);
  if (info == nullptr || info->si_code <= 0) raise(sig);
}

void on_terminate() {
  remove_pending();
  const char* cause = "std::terminate called";
  if (std::exception_ptr e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::exception& x) {
      static char what[256];
      std::snprintf(what, sizeof what, "%s", x.what());
      cause = what;
    } catch (...) {
    }
  }
  if (!g_crash_armed.load()) report(g_subject, cause, false);
  report_crash(cause);
}

// A library's own exit() skips our destructors, not atexit.
void remove_pending_at_exit() { remove_pending(); }

}  // namespace

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_fatal_signal;
  sigemptyset(&sa.sa_mask);
  auto install_if_default = [&](int sig) {
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) != 0) return;
    if (old.sa_handler == SIG_DFL && !(old.sa_flags & SA_SIGINFO)) sigaction(sig, &sa, nullptr);
  };
  for (const int sig : terminating) install_if_default(sig);
  for (int sig = SIGRTMIN; sig <= SIGRTMAX; ++sig) install_if_default(sig);

  struct sigaction crash {};
  crash.sa_sigaction = on_crash;
  crash.sa_flags = SA_SIGINFO;
  sigemptyset(&crash.sa_mask);
  for (const int sig : crashes) {
    if (sigaction(sig, nullptr, &g_previous[sig]) != 0) continue;
    if (g_previous[sig].sa_handler == SIG_IGN && !(g_previous[sig].sa_flags & SA_SIGINFO)) continue;
    sigaction(sig, &crash, nullptr);
  }

  std::signal(SIGPIPE, SIG_IGN);
  std::signal(SIGXFSZ, SIG_IGN);
  std::set_terminate(on_terminate);
  std::atexit(remove_pending_at_exit);
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
  for (const int sig : terminating) sigaddset(&block, sig);
  for (int sig = SIGRTMIN; sig <= SIGRTMAX; ++sig) sigaddset(&block, sig);
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

void set_failure_subject(const std::string& name) {
  escape_into(g_subject, sizeof g_subject, name.c_str());
}

crash_means_failure::crash_means_failure(const std::string& what) noexcept {
  escape_into(g_crash_what, sizeof g_crash_what, what.c_str());
  g_crash_armed.store(true);
}

crash_means_failure::~crash_means_failure() { g_crash_armed.store(false); }

void crash_means_failure::fail(const char* cause) noexcept {
  remove_pending();
  report_crash(cause);
}

library_output_silenced::library_output_silenced() noexcept {
  std::fflush(stderr);
  saved_ = fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3);
  const int null_fd = open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (saved_ >= 0 && null_fd >= 0) {
    g_report_fd.store(saved_);
    dup2(null_fd, STDERR_FILENO);
  }
  if (null_fd >= 0) close(null_fd);
}

library_output_silenced::~library_output_silenced() {
  std::fflush(stderr);
  if (saved_ >= 0) {
    dup2(saved_, STDERR_FILENO);
    g_report_fd.store(STDERR_FILENO);
    close(saved_);
  }
}

}  // namespace raycast::io
