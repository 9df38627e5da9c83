// Signals and standard streams, set up once at start: a signal that ends the
// process removes the temporary file being written, then ends it as before.
#pragma once
#include <csignal>
#include <cstddef>

namespace raycast::io {

// Installs the SIGINT/SIGTERM/SIGHUP handler that removes a pending temporary
// file and then dies of the same signal; SIGPIPE becomes an EPIPE error, so a
// reader that stops early is reported as "standard output: Broken pipe".
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

}  // namespace raycast::io
