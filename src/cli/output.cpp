#include "output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <vector>

namespace raycast::cli {
namespace {

// The temporary file a signal must remove; one render writes one file.
char g_pending[4096];
std::atomic<bool> g_has_pending{false};

extern "C" void on_fatal_signal(int sig) {
  if (g_has_pending.load()) unlink(g_pending);
  std::signal(sig, SIG_DFL);
  raise(sig);
}

std::string errno_text(int e) { return std::strerror(e); }

}  // namespace

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_fatal_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGHUP, &sa, nullptr);
  std::signal(SIGPIPE, SIG_IGN);
}

void reserve_standard_streams() noexcept {
  for (int fd = 0; fd <= 2; ++fd) {
    if (fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    const int null_fd = open("/dev/null", O_RDONLY);  // the lowest free number: fd
    if (null_fd >= 0 && null_fd != fd) {
      dup2(null_fd, fd);
      close(null_fd);
    }
  }
}

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
  if (tmpl.size() > sizeof g_pending) throw io_error(dest + ": path too long");
  // Block the handler while the name is registered, so it never sees half of it.
  sigset_t block, old;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  sigaddset(&block, SIGHUP);
  sigprocmask(SIG_BLOCK, &block, &old);
  fd_ = mkstemp(tmpl.data());
  const int e = errno;
  if (fd_ >= 0) {
    temp_ = tmpl.data();
    std::memcpy(g_pending, tmpl.data(), tmpl.size());
    g_has_pending.store(true);
  }
  sigprocmask(SIG_SETMASK, &old, nullptr);
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
    g_has_pending.store(false);
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
  g_has_pending.store(false);
  temp_.clear();
}

}  // namespace raycast::cli
