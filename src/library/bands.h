// Rendering a region of the image into an image sink, a band of rows at a
// time: the one render-and-write loop, shared by the raycast command and the
// library (raycast/raycast.h), whose job::write calls it. Memory is one band, whatever the image size.
#pragma once
#include <cstdint>
#include <functional>

#include "io/image_sink.h"
#include "raycast/description.h"
#include "render/render.h"

namespace raycast {

struct band_timings {
  double render = 0, write = 0;  // seconds
};

// Called before each band is rendered ("rendering") and written ("writing"),
// with the region's rows done so far.
using band_progress = std::function<void(int64_t rows_done, const char* phase)>;

// Renders `region` with `r` in bands and writes them to `sink` in `format`,
// then finishes the sink (renames the file into place). Throws io::io_error
// (the sink's, or a band that cannot be allocated, naming `name`); the sink's
// destructor removes a temporary file on any exception.
band_timings render_to_sink(const renderer& r, const api::region& region, pixel_format format,
                            io::image_sink& sink, const std::string& name, const band_progress& progress = {});

}  // namespace raycast
