#include "image_sink.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <cstdlib>
#include <string>

#include "image_module.h"
#include "output.h"

namespace raycast::cli {
namespace {

// Binary PPM (P6), 8-bit: written by hand, no image library loaded.
class ppm_sink final : public image_sink {
 public:
  ppm_sink(const job& j, int fd, std::unique_ptr<atomic_file> file)
      : file_(std::move(file)), fd_(fd), name_(file_ ? j.output : "standard output"),
        width_(j.sc.cam.image_width) {
    const std::string header = "P6\n" + std::to_string(j.sc.cam.image_width) + " " +
                               std::to_string(j.sc.cam.image_height) + "\n255\n";
    write_all(fd_, header.data(), header.size(), name_);
  }
  void write_rows(int64_t y0, int64_t y1, const unsigned char* data, size_t stride) override {
    const size_t row_bytes = size_t(width_) * 3;
    if (stride == row_bytes) {
      write_all(fd_, data, row_bytes * size_t(y1 - y0), name_);
      return;
    }
    for (int64_t y = y0; y < y1; ++y) write_all(fd_, data + size_t(y - y0) * stride, row_bytes, name_);
  }
  void finish() override {
    if (file_) file_->commit();
  }

 private:
  std::unique_ptr<atomic_file> file_;
  int fd_;
  std::string name_;
  int64_t width_;
};

std::string executable_dir() {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  std::string path(buf, size_t(n));
  return path.substr(0, path.find_last_of('/'));
}

// dlopen the image module: beside the executable (build tree), or in
// <prefix>/<libdir>/raycast relative to <prefix>/bin (install).
const raycast_image_module* load_image_module(const std::string& for_file) {
  static const raycast_image_module* cached = nullptr;
  if (cached) return cached;
  const std::string dir = executable_dir();
  std::string tried, last_error;
  for (const std::string& candidate :
       {dir + "/raycast_oiio.so", dir + "/" RAYCAST_MODULE_RELDIR "/raycast_oiio.so"}) {
    void* h = dlopen(candidate.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!h) {
      const char* e = dlerror();
      last_error = e ? e : candidate;
      continue;
    }
    using get_fn = const raycast_image_module* (*)();
    auto get = reinterpret_cast<get_fn>(dlsym(h, "raycast_image_module_get"));
    const raycast_image_module* m = get ? get() : nullptr;
    if (!m || m->abi_version != RAYCAST_IMAGE_MODULE_ABI) {
      last_error = candidate + ": not a raycast image module of this version";
      continue;
    }
    return cached = m;
  }
  throw io_error(for_file + ": cannot load the image module (" + last_error + ")");
}

class module_sink final : public image_sink {
 public:
  module_sink(const job& j, std::unique_ptr<atomic_file> file)
      : file_(std::move(file)), module_(load_image_module(j.output)) {
    char err[512] = "";
    writer_ = module_->open(file_->fd(), std::string(to_string(j.format)).c_str(),
                            j.sc.cam.image_width, j.sc.cam.image_height,
                            is_float_format(j.format) ? 1 : 0, err, sizeof err);
    if (!writer_) throw io_error(j.output + ": " + err);
  }
  ~module_sink() override {
    if (writer_) module_->abandon(writer_);  // finish() was not reached: a failure
  }
  void write_rows(int64_t y0, int64_t y1, const unsigned char* data, size_t stride) override {
    char err[512] = "";
    if (module_->write_rows(writer_, y0, y1, data, stride, err, sizeof err) != 0)
      throw io_error(file_->dest() + ": " + err);
  }
  void finish() override {
    char err[512] = "";
    const int rc = module_->close(writer_, err, sizeof err);
    writer_ = nullptr;
    if (rc != 0) throw io_error(file_->dest() + ": " + err);
    file_->commit();
  }

 private:
  std::unique_ptr<atomic_file> file_;
  const raycast_image_module* module_;
  raycast_image_writer* writer_ = nullptr;
};

}  // namespace

pixel_format sink_pixel_format(const job& j) {
  return is_float_format(j.format) ? pixel_format::rgb_f32 : pixel_format::rgb8;
}

std::unique_ptr<image_sink> open_sink(const job& j) {
  if (j.output == "-") return std::make_unique<ppm_sink>(j, STDOUT_FILENO, nullptr);
  auto file = std::make_unique<atomic_file>(j.output);
  if (j.format == file_format::ppm) {
    const int fd = file->fd();
    return std::make_unique<ppm_sink>(j, fd, std::move(file));
  }
  return std::make_unique<module_sink>(j, std::move(file));
}

}  // namespace raycast::cli
