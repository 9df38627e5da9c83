#include "atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <cerrno>
#include <cstring>
#include <vector>

#include "signals.h"

namespace raycast::io {
namespace {

std::string errno_text(int e) { return std::strerror(e); }

}  // namespace

void write_all(int fd, const void* data, size_t n, const std::string& name) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw io_error(name + ": " + errno_text(w < 0 ? errno : EIO));
    p += w;
    n -= size_t(w);
  }
}

atomic_file::atomic_file(const std::string& dest) : dest_(dest) {
  struct stat st {};
  const bool exists = stat(dest.c_str(), &st) == 0;  // follows symbolic links
  if (exists && S_ISDIR(st.st_mode)) throw io_error(dest + ": " + errno_text(EISDIR));
  if (exists && !S_ISREG(st.st_mode)) {
    // A device or a pipe (/dev/null, /dev/stdout, a FIFO) is written in place:
    // renaming a file over it would replace the node, not write to it.
    fd_ = open(dest.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) throw io_error(dest + ": " + errno_text(errno));
    return;
  }
  // Through a symbolic link, replace the file it names and keep the link.
  target_ = dest;
  struct stat lst {};
  if (exists && lstat(dest.c_str(), &lst) == 0 && S_ISLNK(lst.st_mode)) {
    if (char* real = realpath(dest.c_str(), nullptr)) {
      target_ = real;
      std::free(real);
    }
  }
  const size_t slash = target_.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "" : target_.substr(0, slash + 1);
  const std::string base = slash == std::string::npos ? target_ : target_.substr(slash + 1);
  if (base.empty()) throw io_error(dest + ": " + errno_text(EISDIR));

  const std::string pattern = dir + "." + base + ".XXXXXX";
  std::vector<char> tmpl(pattern.begin(), pattern.end());
  tmpl.push_back('\0');
  if (tmpl.size() > pending_path_capacity) throw io_error(dest + ": path too long");
  // Signals blocked until the name is registered: a signal between mkstemp and
  // the registration would leave the file behind.
  int e = 0;
  {
    const fatal_signals_blocked blocked;
    fd_ = mkstemp(tmpl.data());
    e = errno;
    if (fd_ >= 0) {
      temp_ = tmpl.data();
      register_pending_temporary(tmpl.data());
    }
  }
  if (fd_ < 0) throw io_error(dest + ": " + errno_text(e));
  // mkstemp makes 0600. Replacing a file keeps its permissions; a new file gets
  // what the umask allows, as with open().
  mode_t mode = 0;
  if (exists) {
    mode = st.st_mode & 07777;
  } else {
    const mode_t mask = umask(0);
    umask(mask);
    mode = 0666 & ~mask;
  }
  fchmod(fd_, mode);
}

atomic_file::~atomic_file() { discard(); }

void atomic_file::discard() noexcept {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
  if (!temp_.empty()) {
    // Unlink first, then forget: a signal in between unlinks a name that is
    // already gone (harmless); the other order could leave the file behind.
    unlink(temp_.c_str());
    forget_pending_temporary();
    temp_.clear();
  }
}

void atomic_file::commit() {
  int e = 0;
  if (fsync(fd_) != 0 && errno != EINVAL && errno != EROFS) e = errno;
  if (close(fd_) != 0 && e == 0) e = errno;
  fd_ = -1;
  if (e == 0 && !temp_.empty() && rename(temp_.c_str(), target_.c_str()) != 0) e = errno;
  if (e != 0) {
    discard();
    throw io_error(dest_ + ": " + errno_text(e));
  }
  forget_pending_temporary();
  temp_.clear();
}

}  // namespace raycast::io
