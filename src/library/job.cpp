// raycast/raycast.h: a job (a checked, prepared render) and the writers.
#include <chrono>

#include "io/image_sink.h"
#include "io/module/module_loader.h"
#include "library/bands.h"
#include "library/pipeline.h"
#include "raycast/raycast.h"
#include "render/render.h"
#include "scene/scene.h"

namespace raycast::api {
namespace {

[[noreturn]] void invalid(std::string field, std::string message) {
  throw error(error::kind::invalid_argument, std::move(field), std::move(message));
}

// What a description cannot render: its own rules, and options that would
// act on nothing (--precision fast where spheres are always exact).
void check(const scene& s, const options& o) {
  if (s.arrays) {
    const sphere_arrays& a = *s.arrays;
    if (!s.spheres.empty()) invalid("spheres", "give spheres or arrays, not both");
    if (a.count > 0 && (!a.centers.data || !a.radii.data))
      invalid(a.centers.data ? "radii" : "centers", "is missing for " + std::to_string(a.count) + " spheres");
    for (size_t k = 0; a.shades && k < a.count; ++k)
      if (uint8_t(a.shades[k]) > uint8_t(shading::lit)) invalid("spheres[" + std::to_string(k) + "].shade", "is not a shading");
    if (uint8_t(a.shade) > uint8_t(shading::lit)) invalid("shade", "is not a shading");
  }
  if (auto e = validate(s)) invalid(path(*e), e->message);
  if (o.precision == "fast" && s.sphere_count() > 0)
    invalid("precision", "fast applies to the sky alone (a scene with spheres renders exactly; give exact)");
}

pixel_format internal(pixel_type t) { return t == pixel_type::rgb8 ? pixel_format::rgb8 : pixel_format::rgb_f32; }

void find_installed_module() {
#ifdef RAYCAST_INSTALLED_MODULE_DIR
  io::add_image_module_dir(RAYCAST_INSTALLED_MODULE_DIR);
#endif
}

io::file_format file_format_for(const std::string& path, const std::string& format) try {
  return output_format(path, format, front_end::library);
} catch (const refusal& r) {
  throw library_error(r);
}

void check_sides(io::file_format f, int64_t w, int64_t h) try {
  raycast::check_sides(f, region{0, 0, w, h}, {}, front_end::library);
} catch (const refusal& r) {
  throw library_error(r);
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

struct job::impl {
  std::optional<renderer> r;
  region reg;
  size_t spheres = 0;

  void build(const raycast::scene& sc, const options& o) {
    const render_options ro = renderer_options(o);
    try {
      reg = output_region(o, sc.cam.image_width, sc.cam.image_height, front_end::library);
    } catch (const refusal& x) {
      throw library_error(x);
    }
    spheres = sc.sphere_count();
    try {
      r.emplace(sc, ro);
    } catch (const unsupported_backend& e) {
      throw error(error::kind::unsupported_backend, "backend", e.what());
    }
  }
};

job::job(const scene& s, const options& o) : p_(std::make_unique<impl>()) {
  check(s, o);
  p_->build(make_scene(s), o);
}

job::job(scene&& s, const options& o) : p_(std::make_unique<impl>()) {
  check(s, o);
  p_->build(make_scene(std::move(s)), o);
}

job::~job() = default;
job::job(job&&) noexcept = default;
job& job::operator=(job&&) noexcept = default;

int64_t job::width() const { return p_->reg.width(); }
int64_t job::height() const { return p_->reg.height(); }
std::string job::backend() const { return std::string(to_string(p_->r->selected())); }

job::stats job::statistics() const {
  const renderer& r = *p_->r;
  return {r.light_seconds(), r.light_bytes() - r.light_list_bytes(), r.samples(), p_->spheres,
          r.light_lists(), r.light_list_seconds(), r.light_list_bytes()};
}

void job::render_into(void* data, size_t stride, pixel_type pixels) const {
  const region& g = p_->reg;
  p_->r->render(image_band{data, stride, internal(pixels), g.y0, g.y1, g.x0, g.x1});
}

image job::render(pixel_type pixels) const {
  image img;
  img.width = width();
  img.height = height();
  img.pixels = pixels;
  img.data.resize(img.stride() * size_t(img.height));
  render_into(img.data.data(), img.stride(), pixels);
  return img;
}

job::timings job::write(const std::string& path, const std::string& format, const progress_fn& progress) const {
  const io::file_format f = file_format_for(path, format);
  check_sides(f, width(), height());
  find_installed_module();
  try {
    const auto start = std::chrono::steady_clock::now();
    auto sink = io::open_sink(path, f, width(), height());
    const double open = seconds_since(start);
    const band_timings t = render_to_sink(*p_->r, p_->reg, io::pixel_format_for(f), *sink, path, progress);
    return {open, t.render, t.write};
  } catch (const io::io_error& e) {
    throw error(error::kind::io, "path", e.what());
  }
}

image render(const scene& s, const options& o) { return job(s, o).render(o.pixels); }

void render_to_file(const scene& s, const options& o, const std::string& path) {
  file_format_for(path, o.format);  // a bad name fails before any rendering
  job(s, o).write(path, o.format);
}

void write(const std::string& path, const void* data, size_t stride, int64_t width, int64_t height,
           pixel_type pixels, const std::string& format) {
  const io::file_format f = file_format_for(path, format);
  if (width < 1 || height < 1) invalid("image", "must have at least one pixel");
  if (internal(pixels) != io::pixel_format_for(f))
    invalid("image", std::string(io::display_name(f)) +
                         (io::is_float_format(f) ? " takes float32 pixels" : " takes uint8 pixels"));
  check_sides(f, width, height);
  find_installed_module();
  try {
    auto sink = io::open_sink(path, f, width, height);
    sink->write_rows(0, height, static_cast<const unsigned char*>(data), stride);
    sink->finish();
  } catch (const io::io_error& e) {
    throw error(error::kind::io, "path", e.what());
  }
}

void write(const std::string& path, const image& img, const std::string& format) {
  write(path, img.data.data(), img.stride(), img.width, img.height, img.pixels, format);
}

}  // namespace raycast::api
