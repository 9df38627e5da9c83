// raycast_oiio.so: PNG, JPEG, TIFF and OpenEXR output through OpenImageIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <memory>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "io/module/image_module.h"

namespace {

using OIIO::Filesystem::IOProxy;

// Writes to a caller's descriptor at explicit offsets; remembers the first error, never short.
class fd_proxy final : public IOProxy {
 public:
  explicit fd_proxy(int fd) : IOProxy("", IOProxy::Write), fd_(fd) {
    seekable_ = lseek(fd, 0, SEEK_CUR) >= 0;
  }
  const char* proxytype() const override { return "raycast_fd"; }
  size_t write(const void* buf, size_t size) override {
    const size_t n = pwrite(buf, size, m_pos);
    m_pos += int64_t(size);
    return n;
  }
  // A pipe or a terminal takes the bytes in order (going back: ESPIPE), a file at their offset.
  size_t pwrite(const void* buf, size_t size, int64_t offset) override {
    const char* p = static_cast<const char*>(buf);
    size_t left = size;
    if (!seekable_ && offset != end_ && errno_ == 0) errno_ = ESPIPE;
    while (left > 0 && errno_ == 0) {
      const ssize_t n = seekable_ ? ::pwrite(fd_, p, left, offset) : ::write(fd_, p, left);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        errno_ = n < 0 ? errno : EIO;
        break;
      }
      p += n;
      left -= size_t(n);
      offset += n;
    }
    end_ = std::max(end_, offset);
    return size;  // never short: the encoder runs to the end; close() reports
  }
  // TIFF reads back what it wrote (directories); the descriptor is read-write.
  size_t read(void* buf, size_t size) override {
    const size_t n = pread(buf, size, m_pos);
    m_pos += int64_t(n);
    return n;
  }
  size_t pread(void* buf, size_t size, int64_t offset) override {
    const ssize_t n = ::pread(fd_, buf, size, offset);
    return n < 0 ? 0 : size_t(n);
  }
  size_t size() const override { return size_t(end_); }
  int error() const { return errno_; }

 private:
  int fd_;
  bool seekable_ = true;
  int errno_ = 0;
  int64_t end_ = 0;
};

const char* oiio_format_name(const std::string& f) {
  if (f == "png") return "png";
  if (f == "jpg") return "jpeg";
  if (f == "tif") return "tiff";
  if (f == "exr") return "openexr";
  return nullptr;
}

// While alive, standard error goes to /dev/null (the encoders' complaints about a discarded file).
class stderr_silenced {
 public:
  stderr_silenced() {
    std::fflush(stderr);
    saved_ = fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3);
    const int null_fd = open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ >= 0 && null_fd >= 0) dup2(null_fd, STDERR_FILENO);
    if (null_fd >= 0) close(null_fd);
  }
  ~stderr_silenced() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      dup2(saved_, STDERR_FILENO);
      close(saved_);
    }
  }
  stderr_silenced(const stderr_silenced&) = delete;
  stderr_silenced& operator=(const stderr_silenced&) = delete;

 private:
  int saved_ = -1;
};

// OpenImageIO and OpenEXR start thread pools as wide as the machine, and a thread that cannot
// start terminates the process. So, once, start that many ourselves; where some cannot, both
// libraries work on the calling thread alone.
void fit_thread_pools_to_limits() {
  static std::once_flag once;
  std::call_once(once, [] {
    const unsigned wanted = std::max(1u, std::min(std::thread::hardware_concurrency(), 64u));
    std::mutex hold;
    std::vector<std::thread> started;
    bool all = true;
    {
      const std::lock_guard<std::mutex> lock(hold);
      try {
        while (started.size() < wanted)
          started.emplace_back([&hold] { const std::lock_guard<std::mutex> wait(hold); });
      } catch (const std::system_error&) {
        all = false;
      }
    }
    for (std::thread& t : started) t.join();
    if (!all) {
      OIIO::attribute("threads", 1);
      OIIO::attribute("exr_threads", -1);  // no OpenEXR pool at all
    }
  });
}

void set_err(char* err, size_t len, const std::string& msg) {
  if (err && len) std::snprintf(err, len, "%s", msg.c_str());
}

// OpenImageIO's messages can span lines; the CLI prints one.
std::string one_line(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  for (char& c : s)
    if (c == '\n') c = ' ';
  return s.empty() ? "unknown OpenImageIO error" : s;
}

}  // namespace

struct raycast_image_writer {
  std::unique_ptr<fd_proxy> proxy;
  std::unique_ptr<OIIO::ImageOutput> out;
  OIIO::TypeDesc type;
  int64_t width = 0;
};

namespace {

// Error state after a call: the proxy's failed write first (the cause); OpenImageIO's always read.
bool failed(raycast_image_writer* w, bool ok, char* err, size_t len) {
  const std::string oiio_error =
      w->out && w->out->has_error() ? one_line(w->out->geterror()) : std::string();
  if (w->proxy->error() != 0) {
    set_err(err, len, std::strerror(w->proxy->error()));
    return true;
  }
  if (!oiio_error.empty()) {
    set_err(err, len, oiio_error);
    return true;
  }
  if (!ok) {
    set_err(err, len, "OpenImageIO reported failure without a message");
    return true;
  }
  return false;
}

void abandon_writer(raycast_image_writer* w) {
  std::unique_ptr<raycast_image_writer> owned(w);
  if (!w || !w->out) return;
  const stderr_silenced quiet;
  w->out->close();
  if (w->out->has_error()) w->out->geterror();  // leave no message pending
  w->out.reset();  // before the proxy it writes through
}

raycast_image_writer* open_writer(int fd, const char* format, int64_t width, int64_t height,
                                  int is_float, int64_t timestamp, char* err, size_t errlen) {
  const char* name = oiio_format_name(format ? format : "");
  if (!name) {
    set_err(err, errlen, std::string("unsupported format ") + (format ? format : "(null)"));
    return nullptr;
  }
  fit_thread_pools_to_limits();
  auto w = std::make_unique<raycast_image_writer>();
  w->proxy = std::make_unique<fd_proxy>(fd);
  w->out = OIIO::ImageOutput::create(name);
  if (!w->out) {
    set_err(err, errlen, one_line(OIIO::geterror()));
    return nullptr;
  }
  w->type = is_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  w->width = width;
  OIIO::ImageSpec spec(int(width), int(height), 3, w->type);
  // No EXIF data (the TIFF writer fails to write its empty directory through a proxy).
  spec.attribute("tiff:write_exif", 0);
  // PNG: zlib's fastest level and every row's "sub" filter (libpng's
  // PNG_FILTER_SUB) in place of level 6 and the adaptive choice: a third of
  // the time (a 1920x1080 frame of spheres writes in about as long as it
  // renders, not ten times as long), files 1.1-1.7x larger.
  spec.attribute("png:compressionLevel", 1);
  spec.attribute("png:filter", 16);
  // Classic TIFF's offsets are 32-bit: BigTIFF past 4 GiB (with room for the directories).
  if (uint64_t(width) * uint64_t(height) * 3 * w->type.size() > (uint64_t{15} << 28))
    spec.attribute("tiff:bigtiff", 1);
  if (timestamp >= 0) {
    const time_t t = time_t(timestamp);
    struct tm tm {};
    char date[32];
    if (gmtime_r(&t, &tm) && std::strftime(date, sizeof date, "%Y:%m:%d %H:%M:%S", &tm) > 0)
      spec.attribute("DateTime", date);
  }
  if (!w->out->set_ioproxy(w->proxy.get())) {
    set_err(err, errlen, std::string(name) + " writer cannot write through an I/O proxy");
    return nullptr;
  }
  const bool ok = w->out->open(std::string("raycast.") + format, spec);
  if (failed(w.get(), ok, err, errlen)) {
    abandon_writer(w.release());
    return nullptr;
  }
  return w.release();
}

int write_rows(raycast_image_writer* w, int64_t y0, int64_t y1, const void* data, size_t stride,
               char* err, size_t errlen) {
  const OIIO::stride_t xstride = OIIO::stride_t(3 * w->type.size());
  const bool ok = w->out->write_scanlines(int(y0), int(y1), 0, w->type, data, xstride,
                                          OIIO::stride_t(stride));
  return failed(w, ok, err, errlen) ? 1 : 0;
}

int close_writer(raycast_image_writer* w, char* err, size_t errlen) {
  std::unique_ptr<raycast_image_writer> owned(w);
  const bool ok = w->out->close();
  const int rc = failed(w, ok, err, errlen) ? 1 : 0;
  w->out.reset();  // before the proxy it writes through
  return rc;
}

const raycast_image_module module_table = {RAYCAST_IMAGE_MODULE_ABI, open_writer, write_rows,
                                           close_writer, abandon_writer};

}  // namespace

extern "C" __attribute__((visibility("default"))) const raycast_image_module*
raycast_image_module_get(void) {
  return &module_table;
}
