// Writing files without damaging what is there: everything goes to a temporary
// file beside the destination, which is renamed over it only after every write,
// flush and close succeeded. SIGINT/SIGTERM remove the temporary file. A
// replaced file keeps its permissions; through a symbolic link the file it
// names is replaced. A destination that is a device or a pipe is written in
// place (there is nothing to rename over).
#pragma once
#include <cstddef>
#include <stdexcept>
#include <string>

namespace raycast::cli {

// A failure to report as "raycast: error: <what>" with exit code 1; the
// message names the file and the cause.
struct io_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Writes all n bytes or throws io_error("<name>: <strerror>").
void write_all(int fd, const void* data, size_t n, const std::string& name);

class atomic_file {
 public:
  // Creates ".<name>.XXXXXX" beside dest (or opens the device). Throws io_error.
  explicit atomic_file(const std::string& dest);
  ~atomic_file();  // removes the temporary file unless committed
  atomic_file(const atomic_file&) = delete;
  atomic_file& operator=(const atomic_file&) = delete;

  int fd() const { return fd_; }
  const std::string& dest() const { return dest_; }
  // fsync, close, rename over dest. Throws io_error (the temporary is removed).
  void commit();

 private:
  void discard() noexcept;
  std::string dest_, target_, temp_;  // temp_ empty: writing a device in place
  int fd_ = -1;
};

// Installs the SIGINT/SIGTERM/SIGHUP handler that removes a pending temporary
// file and then dies of the same signal; SIGPIPE becomes an EPIPE error, so a
// reader that stops early is reported as "standard output: Broken pipe".
void install_signal_handlers();

// A standard stream (0, 1, 2) that is closed when raycast starts is opened
// read-only on /dev/null, so that no file raycast opens later takes its number
// and a write to it fails with EBADF: `raycast -o - >&-` reports "standard
// output: Bad file descriptor" instead of writing the image somewhere else.
void reserve_standard_streams() noexcept;

}  // namespace raycast::cli
