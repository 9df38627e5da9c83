#include "io/image_sink.h"

#include <sys/stat.h>
#include <unistd.h>

#include <optional>
#include <string>
#include <utility>

#include "io/files/atomic_file.h"
#include "io/module/module_loader.h"
#include "io/ppm.h"
#include "io/files/signals.h"
#include "io/timestamp.h"

namespace raycast::io {
namespace {

// As gzip: binary data on a terminal is noise and can set its modes.
constexpr const char* terminal_refusal =
    "is a terminal; not writing binary image data to it (redirect it to a file or a pipe)";

class module_sink final : public image_sink {
 public:
  module_sink(const raycast_image_module* module, file_format format, int64_t width, int64_t height,
              std::unique_ptr<atomic_file> file)
      : file_(std::move(file)), module_(module) {
    char err[512] = "";
    const source_date date = source_date_epoch();
    {
      const library_output_silenced quiet;
      writer_ = module_->open(file_->fd(), std::string(to_string(format)).c_str(), width, height,
                              is_float_format(format) ? 1 : 0, date.seconds.value_or(-1), err,
                              sizeof err);
    }
    if (!writer_) throw io_error(file_->dest() + ": " + err);
  }
  ~module_sink() override {
    if (writer_) {  // finish() was not reached: a failure
      const library_output_silenced quiet;
      module_->abandon(writer_);
    }
  }
  void write_rows(int64_t y0, int64_t y1, const unsigned char* data, size_t stride) override {
    call([&](char* err) { return module_->write_rows(writer_, y0, y1, data, stride, err, err_size); });
  }
  void finish() override {
    call([&](char* err) { return module_->close(std::exchange(writer_, nullptr), err, err_size); });
    file_->commit();
  }

 private:
  static constexpr size_t err_size = 512;
  // f(err) with the libraries' output silenced; throws its error where it returns nonzero.
  template <class F>
  void call(const F& f) {
    char err[err_size] = "";
    int rc = 0;
    {
      const library_output_silenced quiet;
      rc = f(err);
    }
    if (rc != 0) throw io_error(file_->dest() + ": " + err);
  }

  std::unique_ptr<atomic_file> file_;
  const raycast_image_module* module_;
  raycast_image_writer* writer_ = nullptr;
};

std::unique_ptr<image_sink> open_stdout_sink(int64_t width, int64_t height) {
  set_failure_subject("standard output");
  if (isatty(STDOUT_FILENO)) throw io_error(std::string("standard output: ") + terminal_refusal);
  return make_ppm_sink(STDOUT_FILENO, "standard output", width, height, nullptr);
}

std::unique_ptr<image_sink> open_file_sink(const std::string& path, file_format format,
                                           int64_t width, int64_t height) {
  set_failure_subject(path);
  // The image module first, before any file exists: loading it is what fails under tight limits.
  const raycast_image_module* module =
      format == file_format::ppm ? nullptr : load_image_module(path);
  // Formats whose encoder goes back cannot stream: refused before a pipe is opened (it would wait).
  const std::string seek_error = path + ": " + std::string(display_name(format)) +
                                 " needs a seekable file, and this is a pipe or a terminal "
                                 "(PPM, PNG and JPEG can stream)";
  struct stat st {};
  if (needs_seekable_file(format) && stat(path.c_str(), &st) == 0 &&
      (S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode)))
    throw io_error(seek_error);
  std::optional<uint64_t> known_size;
  if (format == file_format::ppm) known_size = ppm_file_size(width, height);
  auto file = std::make_unique<atomic_file>(path, known_size);
  if (file->in_place() && isatty(file->fd())) throw io_error(path + ": " + terminal_refusal);
  if (file->in_place() && needs_seekable_file(format) && lseek(file->fd(), 0, SEEK_CUR) < 0)
    throw io_error(seek_error);
  if (format == file_format::ppm) {
    const int fd = file->fd();
    return make_ppm_sink(fd, path, width, height, std::move(file));
  }
  return std::make_unique<module_sink>(module, format, width, height, std::move(file));
}

}  // namespace

std::unique_ptr<image_sink> open_sink(const std::string& path, file_format format, int64_t width, int64_t height) {
  return path == "-" ? open_stdout_sink(width, height) : open_file_sink(path, format, width, height);
}

}  // namespace raycast::io
