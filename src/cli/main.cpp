// raycast: parse, render in bands of rows, hand each band to the sink.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <new>

#include "image_sink.h"
#include "options.h"
#include "output.h"
#include "render.h"

namespace {

using namespace raycast;

// About a million pixels per band: large enough that threads and writes run
// long, small enough that memory does not grow with the image.
constexpr int64_t band_pixels = int64_t{1} << 20;

struct aligned_free {
  void operator()(unsigned char* p) const { std::free(p); }
};

// The lesson's "Scanlines remaining", shown only to a person at a terminal.
class progress {
 public:
  explicit progress(bool enabled) : on_(enabled) {}
  void remaining(int64_t rows) {
    if (on_) std::fprintf(stderr, "\rScanlines remaining: %lld ", static_cast<long long>(rows));
  }
  ~progress() {
    if (on_) std::fputs("\r\033[K", stderr);  // leave a clean line behind
  }

 private:
  bool on_;
};

int run(const cli::job& j) {
  const renderer r(j.sc, j.render);
  const int64_t W = j.sc.cam.image_width, H = j.sc.cam.image_height;
  const pixel_format fmt = cli::sink_pixel_format(j);
  const size_t stride = size_t(W) * bytes_per_pixel(fmt);
  const int64_t band_rows = std::clamp<int64_t>(band_pixels / W, 1, H);

  std::unique_ptr<unsigned char, aligned_free> buffer(
      static_cast<unsigned char*>(std::aligned_alloc(64, (stride * size_t(band_rows) + 63) / 64 * 64)));
  if (!buffer)
    throw cli::io_error(j.output + ": cannot allocate " + std::to_string(stride * size_t(band_rows)) +
                        " bytes for a band of rows");

  auto sink = cli::open_sink(j);
  progress bar(!j.quiet && isatty(STDERR_FILENO));
  for (int64_t y0 = 0; y0 < H; y0 += band_rows) {
    bar.remaining(H - y0);
    const int64_t y1 = std::min(H, y0 + band_rows);
    r.render(image_band{buffer.get(), stride, fmt, y0, y1});
    sink->write_rows(y0, y1, buffer.get(), stride);
  }
  sink->finish();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  cli::parse_result parsed = cli::parse_args(argc, argv, std::cout, std::cerr);
  if (!parsed.run) return parsed.exit_code;
  cli::install_signal_handlers();
  try {
    return run(*parsed.run);
  } catch (const cli::io_error& e) {
    std::cerr << "raycast: error: " << e.what() << "\n";
  } catch (const unsupported_backend& e) {
    std::cerr << "raycast: error: --backend: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "raycast: error: " << parsed.run->output << ": out of memory\n";
  }
  return 1;
}
