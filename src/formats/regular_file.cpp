#include "formats/regular_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace raycast {
namespace {

std::string describe(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory, not a scene file";
  if (S_ISCHR(mode)) return "is a character device, not a regular file";
  if (S_ISBLK(mode)) return "is a block device, not a regular file";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe), not a regular file";
  if (S_ISSOCK(mode)) return "is a socket, not a regular file";
  return "is not a regular file";
}

}  // namespace

std::variant<std::unique_ptr<regular_file>, std::string> regular_file::open(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::string(std::strerror(errno));
  if (!S_ISREG(st.st_mode)) return describe(st.st_mode);
  // O_NONBLOCK: should the name have become a FIFO since, open returns at once
  // and fstat refuses it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return std::string(std::strerror(errno));
  std::unique_ptr<regular_file> f(new regular_file(fd, st));
  if (::fstat(fd, &f->st_) != 0) return std::string(std::strerror(errno));
  if (!S_ISREG(f->st_.st_mode)) return describe(f->st_.st_mode);
  if (f->st_.st_size < 0) return std::string("has a negative size");
  return f;
}

regular_file::~regular_file() { close(); }

void regular_file::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

ptrdiff_t regular_file::read_at(uint64_t offset, size_t n, char* to) const {
  size_t got = 0;
  while (got < n) {
    const ssize_t r = ::pread(fd_, to + got, n - got, off_t(offset + got));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) return -1;
    if (r == 0) break;
    got += size_t(r);
  }
  return ptrdiff_t(got);
}

bool regular_file::unchanged() const {
  struct stat after {};
  char more;
  return ::pread(fd_, &more, 1, off_t(st_.st_size)) == 0 && ::fstat(fd_, &after) == 0 &&
         after.st_size == st_.st_size && after.st_mtim.tv_sec == st_.st_mtim.tv_sec &&
         after.st_mtim.tv_nsec == st_.st_mtim.tv_nsec && after.st_ctim.tv_sec == st_.st_ctim.tv_sec &&
         after.st_ctim.tv_nsec == st_.st_ctim.tv_nsec;
}

}  // namespace raycast
