#include "io/movie.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "io/files/atomic_file.h"

extern char** environ;

namespace raycast::io {
namespace {

std::string lower_extension(const std::string& path) {
  const size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

// ffmpeg's arguments: raw RGB frames on its standard input, the movie to fd 3.
std::vector<std::string> ffmpeg_arguments(movie_kind k, int64_t w, int64_t h, int fps) {
  std::vector<std::string> a = {"ffmpeg", "-hide_banner", "-nostdin", "-loglevel", "error", "-f", "rawvideo",
                                "-pix_fmt", "rgb24", "-s", std::to_string(w) + "x" + std::to_string(h),
                                "-r", std::to_string(fps), "-i", "pipe:0"};
  const std::string even = "pad=ceil(iw/2)*2:ceil(ih/2)*2";  // 4:2:0 chroma wants even sides
  switch (k) {
    case movie_kind::mp4:
      a.insert(a.end(), {"-vf", even, "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "18", "-f", "mp4"});
      break;
    case movie_kind::webm:
      a.insert(a.end(), {"-vf", even, "-c:v", "libvpx", "-pix_fmt", "yuv420p", "-b:v", "4M", "-f", "webm"});
      break;
    case movie_kind::gif:
      a.insert(a.end(), {"-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse", "-f", "gif"});
      break;
  }
  a.insert(a.end(), {"-y", "/proc/self/fd/3"});
  return a;
}

// The last line ffmpeg wrote on its standard error (kept in fd).
std::string last_message(int fd) {
  std::string text(4096, '\0');
  const off_t size = ::lseek(fd, 0, SEEK_END);
  const off_t from = std::max<off_t>(0, size - off_t(text.size()));
  const ssize_t got = ::pread(fd, text.data(), text.size(), from);
  text.resize(got > 0 ? size_t(got) : 0);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const size_t nl = text.find_last_of('\n');
  return nl == std::string::npos ? text : text.substr(nl + 1);
}

}  // namespace

std::optional<movie_kind> movie_kind_of(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "mp4") return movie_kind::mp4;
  if (ext == "webm") return movie_kind::webm;
  if (ext == "gif") return movie_kind::gif;
  return std::nullopt;
}

std::optional<std::string> movie_unavailable() {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (size_t at = 0; at <= dirs.size();) {
    const size_t end = std::min(dirs.find(':', at), dirs.size());
    const std::string dir = dirs.substr(at, end - at);
    if (::access(((dir.empty() ? "." : dir) + "/ffmpeg").c_str(), X_OK) == 0) return std::nullopt;
    at = end + 1;
  }
  return "writing a movie needs ffmpeg, which is not on PATH (Debian: apt-get install ffmpeg)";
}

movie_writer::movie_writer(const std::string& path, movie_kind kind, int64_t width, int64_t height, int fps)
    : path_(path), width_(width), height_(height), file_(std::make_unique<atomic_file>(path)) {
  int in[2];
  if (::pipe2(in, O_CLOEXEC) != 0) fail(std::strerror(errno));
  messages_ = ::memfd_create("ffmpeg-messages", MFD_CLOEXEC);
  if (messages_ < 0) fail(std::strerror(errno));
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, in[0], 0);
  posix_spawn_file_actions_adddup2(&fa, file_->fd(), 3);
  posix_spawn_file_actions_adddup2(&fa, messages_, 2);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  std::vector<std::string> args = ffmpeg_arguments(kind, width, height, fps);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int rc = posix_spawnp(&pid_, "ffmpeg", &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  ::close(in[0]);
  stdin_ = in[1];
  if (rc != 0) {
    pid_ = -1;
    fail("cannot start ffmpeg: " + std::string(std::strerror(rc)));
  }
}

movie_writer::~movie_writer() {
  if (stdin_ >= 0) ::close(stdin_);
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
  }
  if (messages_ >= 0) ::close(messages_);
}  // file_'s destructor removes the temporary

void movie_writer::fail(const std::string& why) { throw io_error(path_ + ": " + why); }

void movie_writer::add_frame(const unsigned char* rgb, size_t stride) {
  const size_t row = size_t(width_) * 3;
  for (int64_t r = 0; r < height_; ++r) {
    const unsigned char* p = rgb + size_t(r) * stride;
    for (size_t done = 0; done < row;) {
      const ssize_t n = ::write(stdin_, p + done, row - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        ::close(stdin_);
        stdin_ = -1;
        ::waitpid(pid_, nullptr, 0);
        pid_ = -1;
        fail("ffmpeg stopped: " + last_message(messages_));
      }
      done += size_t(n);
    }
  }
}

void movie_writer::finish() {
  ::close(stdin_);
  stdin_ = -1;
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) fail("ffmpeg failed: " + last_message(messages_));
  file_->commit();
}

}  // namespace raycast::io
