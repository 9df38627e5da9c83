// Signals, crashes and standard streams, set up once at start. Whatever ends the process (a
// signal, a crash, std::terminate, a library's exit()) first removes the temporary being written.
#pragma once
#include <csignal>
#include <cstddef>
#include <string>

namespace raycast::io {

// Every signal whose default action ends the process gets a handler that removes the pending
// temporary and dies of the same signal; one ignored at start (`nohup`) or already handled is
// left alone. Crashes remove the file and go on to the previous action. SIGPIPE and SIGXFSZ are
// ignored (ordinary write errors then). std::terminate prints one "raycast: error:" line, exit 1.
void install_signal_handlers();

// A standard stream closed at start is opened read-only on /dev/null: writes to it fail with EBADF.
void reserve_standard_streams() noexcept;

// The temporary a fatal signal must remove (registered with signals blocked); false if too long.
constexpr size_t pending_path_capacity = 4096;
bool register_pending_temporary(const char* path) noexcept;
void forget_pending_temporary() noexcept;

// The name std::terminate's line reports a failure under ("standard output", the destination).
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

// While alive, a crash or std::terminate is reported as "raycast: error: <what> (<cause>)", exit
// 1: for code that crashes on its own failures (the image module's libraries, loaded by dlopen).
class crash_means_failure {
 public:
  explicit crash_means_failure(const std::string& what) noexcept;
  ~crash_means_failure();
  crash_means_failure(const crash_means_failure&) = delete;
  crash_means_failure& operator=(const crash_means_failure&) = delete;

  // Reports the failure now, with `cause`, and exits 1 (from any thread).
  [[noreturn]] static void fail(const char* cause) noexcept;
};

// While alive, standard error is /dev/null (the image module's libraries print); reports still get out.
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
