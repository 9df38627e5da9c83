#include "image_sink.h"

#include <unistd.h>

#include <string>

#include "atomic_file.h"
#include "module_loader.h"
#include "ppm.h"

namespace raycast::io {
namespace {

// PNG, JPEG, TIFF, EXR: encoded by the image module into the atomic file.
class module_sink final : public image_sink {
 public:
  module_sink(file_format format, int64_t width, int64_t height, std::unique_ptr<atomic_file> file)
      : file_(std::move(file)), module_(load_image_module(file_->dest())) {
    char err[512] = "";
    writer_ = module_->open(file_->fd(), std::string(to_string(format)).c_str(), width, height,
                            is_float_format(format) ? 1 : 0, err, sizeof err);
    if (!writer_) throw io_error(file_->dest() + ": " + err);
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

std::unique_ptr<image_sink> open_stdout_sink(int64_t width, int64_t height) {
  return make_ppm_sink(STDOUT_FILENO, "standard output", width, height, nullptr);
}

std::unique_ptr<image_sink> open_file_sink(const std::string& path, file_format format,
                                           int64_t width, int64_t height) {
  auto file = std::make_unique<atomic_file>(path);
  if (format == file_format::ppm) {
    const int fd = file->fd();
    return make_ppm_sink(fd, path, width, height, std::move(file));
  }
  return std::make_unique<module_sink>(format, width, height, std::move(file));
}

}  // namespace raycast::io
