#include "io/files/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "io/files/signals.h"

namespace raycast::io {
namespace {

std::string errno_text(int e) { return std::strerror(e); }

std::string dir_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

// The file a path names, every link in its last component followed (existing or not; over 40: ELOOP).
std::string follow_links(const std::string& path) {
  std::string p = path;
  for (int hops = 0; hops <= 40; ++hops) {
    struct stat st {};
    if (lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    std::vector<char> buf(size_t(st.st_size > 0 ? st.st_size : 255) + 1);
    const ssize_t n = readlink(p.c_str(), buf.data(), buf.size());
    if (n < 0 || size_t(n) >= buf.size()) throw io_error(path + ": " + errno_text(n < 0 ? errno : ENAMETOOLONG));
    const std::string to(buf.data(), size_t(n));
    p = to.front() == '/' ? to : dir_of(p) + to;
  }
  throw io_error(path + ": " + errno_text(ELOOP));
}

// A name no other file has, for the temporary: ".<base>.XXXXXX".
std::string temporary_name(const std::string& dir, const std::string& base, unsigned attempt) {
  static constexpr char letters[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  struct timespec ts {};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  uint64_t x = uint64_t(ts.tv_nsec) * 6364136223846793005ull + uint64_t(getpid()) * 1442695040888963407ull +
               attempt * 0x9e3779b97f4a7c15ull;
  std::string suffix(6, 'X');
  for (char& c : suffix) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    c = letters[(x >> 33) % (sizeof letters - 1)];
  }
  return dir + "." + base + "." + suffix;
}

// "2.3 GB" style, for messages about sizes.
std::string human_size(uint64_t bytes) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
  double v = double(bytes);
  int u = 0;
  while (v >= 1000 && u < 6) {
    v /= 1000;
    ++u;
  }
  char buf[32];
  if (u == 0) std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(bytes));
  else std::snprintf(buf, sizeof buf, "%.1f %s", v, units[u]);
  return buf;
}

// Refuses an image of `bytes` that the file system of dir cannot hold.
void check_free_space(const std::string& dest, const std::string& dir, uint64_t bytes) {
  struct statvfs vfs {};
  if (statvfs(dir.c_str(), &vfs) != 0) return;
  // root may use the blocks reserved for it; others may not.
  const uint64_t blocks = geteuid() == 0 ? vfs.f_bfree : vfs.f_bavail;
  const uint64_t free_bytes = blocks * uint64_t(vfs.f_frsize);
  if (bytes > free_bytes)
    throw io_error(dest + ": the image needs " + std::to_string(bytes) + " bytes (" + human_size(bytes) +
                   ") but its file system has " + std::to_string(free_bytes) + " bytes (" + human_size(free_bytes) +
                   ") free");
}

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

atomic_file::atomic_file(const std::string& dest, std::optional<uint64_t> known_size) : dest_(dest) {
  struct stat st {};
  bool exists = stat(dest.c_str(), &st) == 0;  // follows symbolic links
  // ENOENT: nothing there, or a dangling link; anything else (a loop, say) is the answer.
  if (!exists && errno != ENOENT) throw io_error(dest + ": " + errno_text(errno));
  if (exists && S_ISDIR(st.st_mode)) throw io_error(dest + ": " + errno_text(EISDIR));
  if (exists && !S_ISREG(st.st_mode)) {
    // A device or a pipe is written in place: a rename would replace the node.
    fd_ = open(dest.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) throw io_error(dest + ": " + errno_text(errno));
    in_place_ = true;
    return;
  }
  // Through a symbolic link, replace (or create) the file it names.
  target_ = follow_links(dest);
  dir_ = dir_of(target_);
  base_ = target_.substr(dir_.size());
  if (base_.empty()) throw io_error(dest + ": " + errno_text(EISDIR));
  const std::string dir_or_dot = dir_.empty() ? "." : dir_;
  // The temporary's name, "." + base + ".XXXXXX", must fit NAME_MAX and PATH_MAX (4096 with NUL).
  const long name_max = pathconf(dir_or_dot.c_str(), _PC_NAME_MAX);
  const size_t path_room = dir_.size() + 16 < 4096 ? 4095 - 8 - dir_.size() : 1;
  const size_t keep = std::max<size_t>(1, std::min(size_t(name_max > 8 ? name_max : 255) - 8, path_room));
  size_t cut = std::min(base_.size(), keep);
  while (cut < base_.size() && cut > 1 && (static_cast<unsigned char>(base_[cut]) & 0xc0) == 0x80) --cut;  // whole characters
  temp_base_ = base_.substr(0, cut);

  // A file its owner made read-only is refused, as `cp` and `>` do (a rename would succeed).
  if (exists && faccessat(AT_FDCWD, target_.c_str(), W_OK, AT_EACCESS) != 0)
    throw io_error(dest + ": " + errno_text(errno));

  if (known_size) check_free_space(dest, dir_or_dot, *known_size);
  open_temporary(dir_or_dot);
  keep_owner_and_mode(exists ? &st : nullptr);
}

void atomic_file::open_temporary(const std::string& dir_or_dot) {
  // An unnamed file first (naming it at the end needs /proc/self/fd).
  if (access("/proc/self/fd", X_OK) == 0) {
    fd_ = open(dir_or_dot.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    anonymous_ = fd_ >= 0;
  }
  if (fd_ < 0) {
    const std::string pattern = dir_ + "." + temp_base_ + ".XXXXXX";
    std::vector<char> tmpl(pattern.begin(), pattern.end());
    tmpl.push_back('\0');
    if (tmpl.size() > pending_path_capacity) throw io_error(dest_ + ": path too long");
    int e = 0;
    {
      // Signals blocked until the name is registered.
      const fatal_signals_blocked blocked;
      fd_ = mkstemp(tmpl.data());
      e = errno;
      if (fd_ >= 0) {
        temp_ = tmpl.data();
        register_pending_temporary(tmpl.data());
      }
    }
    if (fd_ < 0) throw io_error(dest_ + ": " + errno_text(e));
    fcntl(fd_, F_SETFD, FD_CLOEXEC);
  }
}

void atomic_file::keep_owner_and_mode(const struct stat* existing) {
  // Owner and group where we may set them, then the mode (chown clears set-id bits); new: the umask's.
  mode_t mode = 0;
  if (existing) {
    const struct stat& st = *existing;
    if (st.st_uid != geteuid() || st.st_gid != getegid()) {
      if (fchown(fd_, st.st_uid, st.st_gid) != 0) (void)!fchown(fd_, uid_t(-1), st.st_gid);
    }
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
    // Unlink first, then forget: the other order could leave the file behind.
    unlink(temp_.c_str());
    forget_pending_temporary();
    temp_.clear();
  }
}

void atomic_file::commit() {
  int e = 0;
  if (fsync(fd_) != 0 && errno != EINVAL && errno != EROFS) e = errno;
  if (e == 0 && anonymous_) {
    // Name the unnamed file beside the destination, then rename (linkat cannot replace a file).
    const std::string proc = "/proc/self/fd/" + std::to_string(fd_);
    for (unsigned attempt = 0; e == 0 && temp_.empty(); ++attempt) {
      const std::string name = temporary_name(dir_, temp_base_, attempt);
      if (name.size() + 1 > pending_path_capacity) {
        e = ENAMETOOLONG;
        break;
      }
      const fatal_signals_blocked blocked;
      if (linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) {
        temp_ = name;
        register_pending_temporary(name.c_str());
      } else if (errno != EEXIST || attempt > 100) {
        e = errno;
      }
    }
  }
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
