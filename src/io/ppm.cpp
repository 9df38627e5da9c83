#include "io/ppm.h"

namespace raycast::io {
namespace {

std::string ppm_header(int64_t width, int64_t height) {
  return "P6\n" + std::to_string(width) + " " + std::to_string(height) + "\n255\n";
}

class ppm_sink final : public image_sink {
 public:
  ppm_sink(int fd, std::string name, int64_t width, int64_t height,
           std::unique_ptr<atomic_file> file)
      : file_(std::move(file)), fd_(fd), name_(std::move(name)), width_(width) {
    const std::string header = ppm_header(width, height);
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

}  // namespace

uint64_t ppm_file_size(int64_t width, int64_t height) {
  return ppm_header(width, height).size() + uint64_t(width) * uint64_t(height) * 3;
}

std::unique_ptr<image_sink> make_ppm_sink(int fd, std::string name, int64_t width, int64_t height,
                                          std::unique_ptr<atomic_file> file) {
  return std::make_unique<ppm_sink>(fd, std::move(name), width, height, std::move(file));
}

}  // namespace raycast::io
