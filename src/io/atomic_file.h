// Writing files without damaging what is there: everything goes to a temporary
// file beside the destination, which is renamed over it only after every write,
// flush and close succeeded. A fatal signal removes the temporary file
// (signals.h). A replaced file keeps its permissions; through a symbolic link
// the file it names is replaced. A destination that is a device or a pipe is
// written in place (there is nothing to rename over).
#pragma once
#include <cstddef>
#include <string>

#include "io_error.h"

namespace raycast::io {

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

}  // namespace raycast::io
