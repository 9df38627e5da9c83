// A scene's file opened for reading: only a regular file, never blocking on
// one that is not (a FIFO, a device), and able to say whether it changed
// while it was read. Shared by the JSON and PLY readers.
#pragma once
#include <sys/stat.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <variant>

namespace raycast {

class regular_file {
 public:
  // Opens path: stat first (which neither blocks on a FIFO nor opens a
  // device), then open with O_NONBLOCK and fstat, refusing what is not a
  // regular file. The error is strerror's text or "is a directory, not a
  // scene file", ...
  static std::variant<std::unique_ptr<regular_file>, std::string> open(const std::string& path);
  ~regular_file();
  regular_file(const regular_file&) = delete;
  regular_file& operator=(const regular_file&) = delete;

  uint64_t size() const { return uint64_t(st_.st_size); }  // as fstat gave it on opening
  // Up to n bytes from offset into to (fewer only at the file's end); -1 and
  // errno on a failure.
  ptrdiff_t read_at(uint64_t offset, size_t n, char* to) const;
  // Whether the file is as it was opened: no byte past size(), the same size
  // and modification and change times.
  bool unchanged() const;
  void close();

 private:
  explicit regular_file(int fd, const struct stat& st) : fd_(fd), st_(st) {}
  int fd_;
  struct stat st_;
};

}  // namespace raycast
