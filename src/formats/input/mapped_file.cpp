#include "formats/input/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <variant>

#include "formats/format.h"
#include "formats/regular_file.h"

namespace raycast::formats::input {

std::shared_ptr<const mapped_file> mapped_file::open(const std::string& path) {
  // regular_file's checks and words first (a directory, a FIFO, ...).
  auto checked = regular_file::open(path);
  if (auto* why = std::get_if<std::string>(&checked)) throw format_error(*why, true);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) throw format_error(std::strerror(errno), true);
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size < 0) {
    const int e = errno;
    ::close(fd);
    throw format_error(S_ISREG(st.st_mode) ? std::strerror(e) : "is not a regular file", true);
  }
  const uint64_t size = uint64_t(st.st_size);
  void* p = nullptr;
  if (size > 0) {
    p = ::mmap(nullptr, size_t(size), PROT_READ, MAP_PRIVATE, fd, 0);
    if (p == MAP_FAILED) {
      const int e = errno;
      ::close(fd);
      throw format_error(std::strerror(e), true);
    }
  }
  ::close(fd);  // the mapping stays
  return std::shared_ptr<const mapped_file>(new mapped_file(static_cast<const unsigned char*>(p), size));
}

mapped_file::~mapped_file() {
  if (data_) ::munmap(const_cast<unsigned char*>(data_), size_t(size_));
}

void mapped_file::will_need(uint64_t offset, uint64_t n) const {
  if (!data_ || offset >= size_) return;
  const uint64_t page = uint64_t(::sysconf(_SC_PAGESIZE));
  const uint64_t begin = offset / page * page;
  const uint64_t end = std::min(size_, offset + std::min(n, size_ - offset));
  ::madvise(const_cast<unsigned char*>(data_) + begin, size_t(end - begin), MADV_WILLNEED);
}

}  // namespace raycast::formats::input
