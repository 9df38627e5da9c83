// Writing files without damaging what is there. The image goes to a file
// with no name (O_TMPFILE) in the destination's directory, which is given a
// name and renamed over the destination only after every write, flush and
// fsync succeeded: a process killed even by SIGKILL leaves nothing behind.
// Where the file system has no O_TMPFILE (or /proc is not mounted), a named
// ".<name>.XXXXXX" stands in, which the signal handlers remove (signals.h).
//
// The destination is checked first, as `>` and `cp` would: a file its owner
// made read-only is refused (Permission denied), a symbolic link loop is
// reported, a dangling link gets the file it names created. A replaced file
// keeps its permissions and, where the user may set them, its owner and group;
// through a symbolic link the file it names is replaced. Another hard link to
// the old file keeps the old image (the name is replaced, not the inode: a
// failed write must not damage it). A device or a pipe is written in place.
#pragma once
#include <sys/stat.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "io/io_error.h"

namespace raycast::io {

// Writes all n bytes or throws io_error("<name>: <strerror>").
void write_all(int fd, const void* data, size_t n, const std::string& name);

class atomic_file {
 public:
  // Checks the destination and creates the unnamed (or temporary) file beside
  // it, or opens a device in place. known_size: the exact size the file will
  // have, refused up front when the destination's file system has less free.
  // Throws io_error naming dest and the cause.
  explicit atomic_file(const std::string& dest, std::optional<uint64_t> known_size = std::nullopt);
  ~atomic_file();  // removes the temporary file unless committed
  atomic_file(const atomic_file&) = delete;
  atomic_file& operator=(const atomic_file&) = delete;

  int fd() const { return fd_; }
  const std::string& dest() const { return dest_; }
  bool in_place() const { return in_place_; }  // a device or a pipe
  // fsync, name, rename over dest. Throws io_error (the temporary is removed).
  void commit();

 private:
  // The constructor's steps: a file with no name (or a registered named
  // temporary) in dir_or_dot; then the replaced file's owner and mode
  // (existing: its stat, or null for a new file).
  void open_temporary(const std::string& dir_or_dot);
  void keep_owner_and_mode(const struct stat* existing);
  void discard() noexcept;
  std::string dest_, target_, dir_, base_;
  std::string temp_base_;  // base_, cut so that the temporary's name fits the file system's limit
  std::string temp_;       // the named temporary, while one exists
  bool anonymous_ = false;  // O_TMPFILE: no name until commit()
  bool in_place_ = false;
  int fd_ = -1;
};

// "2.3 GB" style, for messages about sizes.
std::string human_size(uint64_t bytes);

}  // namespace raycast::io
