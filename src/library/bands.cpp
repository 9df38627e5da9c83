#include "library/bands.h"

#include <algorithm>
#include <chrono>
#include <new>
#include <string>

#include "memory/arrays.h"

namespace raycast {

namespace {

// About a million pixels per band: large enough that threads and writes run
// long, small enough that memory does not grow with the image.
constexpr int64_t band_pixels = int64_t{1} << 20;

using clock = std::chrono::steady_clock;
double seconds_since(clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); }

}  // namespace

band_timings render_to_sink(const renderer& r, const api::region& reg, pixel_format fmt, io::image_sink& sink,
                            const std::string& name, const band_progress& progress) {
  band_timings st;
  const int64_t W = reg.width(), H = reg.height();
  const size_t stride = size_t(W) * bytes_per_pixel(fmt);
  // Many samples per pixel: fewer pixels per band, so that a band's work
  // (and the progress between two updates) stays about the same.
  const int64_t pixels = std::max<int64_t>(1, std::min<int64_t>(band_pixels, (band_pixels << 2) / r.samples()));
  const int64_t band_rows = std::clamp<int64_t>(pixels / W, 1, H);

  // Written whole by the render before it is read: in huge pages where
  // small pages are dear (memory/arrays.h).
  filled_later_array<unsigned char> buffer;
  try {
    buffer.resize(stride * size_t(band_rows));
  } catch (const std::bad_alloc&) {
    throw io::io_error(name + ": cannot allocate " + std::to_string(stride * size_t(band_rows)) +
                       " bytes for a band of rows");
  }
  for (int64_t y0 = 0; y0 < H; y0 += band_rows) {
    const int64_t y1 = std::min(H, y0 + band_rows);
    if (progress) progress(y0, "rendering");
    auto t = clock::now();
    r.render(image_band{buffer.data(), stride, fmt, reg.y0 + y0, reg.y0 + y1, reg.x0, reg.x1});
    st.render += seconds_since(t);
    if (progress) progress(y0, "writing");
    t = clock::now();
    sink.write_rows(y0, y1, buffer.data(), stride);
    st.write += seconds_since(t);
  }
  const auto t = clock::now();
  sink.finish();
  st.write += seconds_since(t);
  return st;
}

}  // namespace raycast
