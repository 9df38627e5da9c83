// Signals, crashes and standard streams, set up once at start. Whatever ends
// the process — a signal, a crash in a library, std::terminate, a library's
// own call to exit() — first removes the temporary file being written.
#pragma once
#include <csignal>
#include <cstddef>
#include <string>

namespace raycast::io {

// Every signal whose default action ends the process (SIGINT, SIGTERM,
// SIGHUP, SIGQUIT, SIGXCPU, SIGUSR1, SIGALRM, ..., the real-time signals) gets
// a handler that removes the pending temporary file and then dies of the same
// signal, as it would have. A signal ignored when raycast starts (`nohup`)
// stays ignored, and one a preloaded library already handles is left to it.
// Crashes (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT) remove the file and go on
// to the previous action (the sanitizers' report, or a core dump). SIGPIPE and
// SIGXFSZ are ignored: a reader that stops early becomes "Broken pipe", a file
// over RLIMIT_FSIZE "File too large", both ordinary write errors. An uncaught
// exception (std::terminate) prints one "raycast: error:" line and exits 1.
void install_signal_handlers();

// A standard stream (0, 1, 2) that is closed when raycast starts is opened
// read-only on /dev/null, so that no file raycast opens later takes its number
// and a write to it fails with EBADF: `raycast -o - >&-` reports "standard
// output: Bad file descriptor" instead of writing the image somewhere else.
void reserve_standard_streams() noexcept;

// The temporary file a fatal signal must remove (one render writes one file).
// Registering and forgetting happen with the handled signals blocked, so the
// handler never sees half a name. Returns false when the name is too long
// (longer than pending_path_capacity - 1 bytes).
constexpr size_t pending_path_capacity = 4096;
bool register_pending_temporary(const char* path) noexcept;
void forget_pending_temporary() noexcept;

// The name a failure with no better one is reported under ("standard output",
// the destination file): what std::terminate's line starts with.
void set_failure_subject(const std::string& name);

// Blocks the signals whose handler removes the temporary file, while alive.
class fatal_signals_blocked {
 public:
  fatal_signals_blocked() noexcept;
  ~fatal_signals_blocked();
  fatal_signals_blocked(const fatal_signals_blocked&) = delete;
  fatal_signals_blocked& operator=(const fatal_signals_blocked&) = delete;

 private:
  sigset_t old_;
};

// While alive, a crash or std::terminate is reported as the failure of
// `what` — "raycast: error: <what> (<cause>)", exit 1 — instead of ending the
// process by a signal. For code we do not control that crashes on its own
// failures: the static constructors of the image module's ~260 libraries,
// run by dlopen, abort on bad_alloc or a thread that cannot start and
// dereference failed allocations under an address-space limit.
class crash_means_failure {
 public:
  explicit crash_means_failure(const std::string& what) noexcept;
  ~crash_means_failure();
  crash_means_failure(const crash_means_failure&) = delete;
  crash_means_failure& operator=(const crash_means_failure&) = delete;

  // Reports the failure now, with `cause`, and exits 1 (from any thread).
  [[noreturn]] static void fail(const char* cause) noexcept;
};

// While alive, standard error is /dev/null: around every call into the image
// module, whose libraries print lines of their own ("libpng error: ...",
// libtiff warnings). A failure comes back as an error string, which raycast
// reports once. The crash and terminate reports above still reach the real
// standard error.
class library_output_silenced {
 public:
  library_output_silenced() noexcept;
  ~library_output_silenced();
  library_output_silenced(const library_output_silenced&) = delete;
  library_output_silenced& operator=(const library_output_silenced&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace raycast::io
