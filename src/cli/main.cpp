// raycast: parse, render in bands of rows, hand each band to the sink.
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <new>
#include <string>
#include <string_view>

#include "io/image_sink.h"
#include "io/signals.h"
#include "io/timestamp.h"
#include "options.h"
#include "render/render.h"
#include "simd/cpu.h"

namespace {

using namespace raycast;

// About a million pixels per band: large enough that threads and writes run
// long, small enough that memory does not grow with the image.
constexpr int64_t band_pixels = int64_t{1} << 20;

struct aligned_free {
  void operator()(unsigned char* p) const { std::free(p); }
};

// The lesson's "Scanlines remaining" with a bar and the phase (rendering or
// writing a band), shown only to a person at a terminal.
class progress {
 public:
  progress(bool enabled, int64_t rows) : on_(enabled), rows_(rows) {}
  void show(int64_t rows_done, const char* phase) {
    if (!on_) return;
    constexpr int width = 30;
    const int filled = int(width * rows_done / rows_);
    std::fprintf(stderr, "\rScanlines remaining: %lld [%.*s%*s] %3d%% %-9s",
                 static_cast<long long>(rows_ - rows_done), filled,
                 "##############################", width - filled, "",
                 int(100 * rows_done / rows_), phase);
    std::fflush(stderr);
  }
  ~progress() {
    if (on_) std::fputs("\r\033[K", stderr);  // leave a clean line behind
  }

 private:
  bool on_;
  int64_t rows_;
};

int run(const cli::job& j) {
  const renderer r(j.sc, j.render);
  // The output is the region (the whole image unless --region): its rows and
  // columns of the image, rendered in bands of whole region rows.
  const cli::pixel_region& reg = j.region;
  const int64_t W = reg.width(), H = reg.height();
  const pixel_format fmt = io::pixel_format_for(j.format);
  const size_t stride = size_t(W) * bytes_per_pixel(fmt);
  // Many samples per pixel: fewer pixels per band, so that a band's work
  // (and the progress between two updates) stays about the same.
  const int64_t pixels = std::max<int64_t>(1, std::min<int64_t>(band_pixels, (band_pixels << 2) / r.samples()));
  const int64_t band_rows = std::clamp<int64_t>(pixels / W, 1, H);

  std::unique_ptr<unsigned char, aligned_free> buffer(
      static_cast<unsigned char*>(std::aligned_alloc(64, (stride * size_t(band_rows) + 63) / 64 * 64)));
  if (!buffer)
    throw io::io_error(j.output + ": cannot allocate " + std::to_string(stride * size_t(band_rows)) +
                        " bytes for a band of rows");

  auto sink = j.output == "-" ? io::open_stdout_sink(W, H) : io::open_file_sink(j.output, j.format, W, H);
  progress bar(!j.quiet && isatty(STDERR_FILENO), H);
  for (int64_t y0 = 0; y0 < H; y0 += band_rows) {
    const int64_t y1 = std::min(H, y0 + band_rows);
    bar.show(y0, "rendering");
    r.render(image_band{buffer.get(), stride, fmt, reg.y0 + y0, reg.y0 + y1, reg.x0, reg.x1});
    bar.show(y0, "writing");
    sink->write_rows(y0, y1, buffer.get(), stride);
  }
  sink->finish();
  return 0;
}


void print_error(std::string_view what) {
  std::cerr << "raycast: error: " << cli::printable(what) << "\n";
}

// --help and --version print to standard output: a failed write there (closed,
// full, a reader gone) is a failure too, reported like any other.
bool standard_output_flushed() {
  errno = 0;
  std::cout.flush();
  if (std::fflush(stdout) == 0 && !std::ferror(stdout) && std::cout.good()) return true;
  const int e = errno;
  print_error(std::string("standard output: ") + (e != 0 ? std::strerror(e) : "write error"));
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  io::reserve_standard_streams();
  io::install_signal_handlers();
  cli::parse_result parsed = cli::parse_args(argc, argv, std::cout, std::cerr);
  if (!parsed.run) {
    if (parsed.exit_code == 0 && !standard_output_flushed()) return 1;
    return parsed.exit_code;
  }
  // The environment is part of the command: a malformed value is refused
  // like a malformed option, before anything is touched.
  if (auto why = max_isa_error()) {
    print_error("RAYCAST_MAX_ISA: " + *why);
    return 2;
  }
  if (auto why = io::source_date_epoch().error) {
    print_error("SOURCE_DATE_EPOCH: " + *why);
    return 2;
  }
  try {
    return run(*parsed.run);
  } catch (const io::io_error& e) {
    print_error(e.what());
  } catch (const unsupported_backend& e) {
    print_error(std::string("--backend: ") + e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    print_error(parsed.run->output + ": out of memory");
  } catch (const std::exception& e) {
    // Anything else still unwinds, so the temporary file is removed.
    print_error(parsed.run->output + ": " + e.what());
  }
  return 1;
}
