// Writing files without damaging what is there (README.md): the image goes to an unnamed file
// (O_TMPFILE) beside the destination, named and renamed over it only after every write and fsync
// succeeded; without O_TMPFILE (or /proc), a named ".<name>.XXXXXX" that the signal handlers
// remove. The destination is checked first, as `>` and `cp` would; a replaced file keeps its
// permissions and, where allowed, owner and group; the name is replaced, not the inode. A device
// or a pipe is written in place.
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
  // Checks the destination and creates the file beside it, or opens a device in place. known_size:
  // the file's exact size, refused up front beyond the free space. Throws io_error naming dest.
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
  // The constructor's steps (existing: the replaced file's stat, or null).
  void open_temporary(const std::string& dir_or_dot);
  void keep_owner_and_mode(const struct stat* existing);
  void discard() noexcept;
  std::string dest_, target_, dir_, base_;
  std::string temp_base_;  // base_, cut so that the temporary's name fits
  std::string temp_;       // the named temporary, while one exists
  bool anonymous_ = false;  // O_TMPFILE: no name until commit()
  bool in_place_ = false;
  int fd_ = -1;
};

}  // namespace raycast::io
