#include "raycast/raycast.h"

#include <algorithm>
#include <charconv>
#include <new>
#include <string_view>
#include <utility>
#include <variant>

#include "io/format.h"
#include "io/image_sink.h"
#include "io/module_loader.h"
#include "library/bands.h"
#include "settings/inputs.h"
#include "render/render.h"
#include "scene/builtin.h"
#include "settings/names.h"
#include "formats/json.h"

namespace raycast::api {

error::error(enum kind k, std::string field, std::string message)
    : std::runtime_error(field.empty() ? message : field + ": " + message),
      kind_(k),
      field_(std::move(field)),
      message_(std::move(message)) {}

namespace {

[[noreturn]] void invalid(std::string field, std::string message) {
  throw error(error::kind::invalid_argument, std::move(field), std::move(message));
}

// The scene room's shading for ours; lit only where this build has it.
template <class S>
constexpr bool has_lit = requires { S::lit; };

template <class S>
std::optional<S> internal_shading(shading s) {
  switch (s) {
    case shading::normal: return S::normal;
    case shading::flat: return S::flat;
    case shading::lit:
      if constexpr (has_lit<S>) return S::lit;
      else return std::nullopt;
  }
  return std::nullopt;
}

raycast::shading to_internal(shading s, const std::string& field) {
  if (auto v = internal_shading<raycast::shading>(s)) return *v;
  invalid(field, "shade 'lit' is not supported yet by this build");
}

shading from_internal(raycast::shading s) {
  for (shading a : {shading::normal, shading::flat, shading::lit})
    if (internal_shading<raycast::shading>(a) == s) return a;
  return shading::normal;
}

point3 to_internal(const vec3& v) { return point3(v[0], v[1], v[2]); }
vec3 from_internal(const point3& v) { return {v.x, v.y, v.z}; }

// The two element enumerations agree value for value.
sphere_view::column to_internal(const sphere_arrays::column& c, ptrdiff_t packed) {
  const ptrdiff_t size = c.type == sphere_arrays::element::f32 ? 4 : c.type == sphere_arrays::element::u8 ? 1 : 8;
  if (uint8_t(c.type) > uint8_t(sphere_arrays::element::u8)) invalid("arrays", "an element type it does not know");
  const ptrdiff_t stride = c.stride == sphere_arrays::one_for_all ? 0 : c.stride ? c.stride : packed * size;
  return {c.data, sphere_view::element(uint8_t(c.type)), stride,
          c.component_stride ? c.component_stride : size, c.byte_swapped};
}

sphere_arrays::column from_internal(const sphere_view::column& c) {
  return {c.data, sphere_arrays::element(uint8_t(c.type)), c.stride ? c.stride : sphere_arrays::one_for_all,
          c.component_stride, c.swapped};
}

scene_params to_internal(const scene& s) {
  scene_params p;
  camera_params& c = p.camera;
  c.aspect_ratio = s.cam.aspect;
  c.image_width = s.cam.width;
  c.image_height = s.cam.height;
  c.viewport_height = s.cam.viewport_height;
  c.focal_length = s.cam.focal_length;
  c.origin = to_internal(s.cam.lookfrom);
  if (s.cam.lookat) c.lookat = to_internal(*s.cam.lookat);
  c.vup = to_internal(s.cam.vup);
  c.vfov_degrees = s.cam.vfov;
  c.proj = raycast::projection(uint8_t(s.cam.projection));
  p.sky.bottom = to_internal(s.sky.bottom);
  p.sky.top = to_internal(s.sky.top);
  if (s.light.direction) p.light.direction = to_internal(*s.light.direction);
  p.light.shadows = s.light.shadows;
  p.light.ao_samples = s.light.ao_samples;
  p.light.ao_distance = s.light.ao_distance;
  if (s.arrays && !s.spheres.empty()) invalid("spheres", "give spheres or arrays, not both");
  p.spheres.reserve(s.spheres.size());
  for (size_t k = 0; k < s.spheres.size(); ++k) {
    const sphere& a = s.spheres[k];
    p.spheres.push_back(raycast::sphere{to_internal(a.center), a.radius,
                                        to_internal(a.shade, "spheres[" + std::to_string(k) + "].shade"),
                                        to_internal(a.color)});
  }
  if (s.arrays) {
    const sphere_arrays& a = *s.arrays;
    if (a.count > 0 && (!a.centers.data || !a.radii.data))
      invalid(a.centers.data ? "radii" : "centers", "is missing for " + std::to_string(a.count) + " spheres");
    sphere_view v;
    v.count = a.count;
    v.centers = to_internal(a.centers, 3);
    v.radii = to_internal(a.radii, 1);
    if (a.colors.data) v.colors = to_internal(a.colors, 3);
    v.shade = to_internal(a.shade, "shade");
    v.owner = a.owner;
    if (a.shades) {
      // Read in place: the two enumerations agree value for value.
      for (size_t k = 0; k < a.count; ++k) {
        const std::string field = "spheres[" + std::to_string(k) + "].shade";
        if (uint8_t(a.shades[k]) > uint8_t(shading::lit)) invalid(field, "is not a shading");
        if (uint8_t(to_internal(a.shades[k], field)) != uint8_t(a.shades[k]))
          invalid(field, "per-sphere shading does not match this build's");
      }
      v.shades = reinterpret_cast<const raycast::shading*>(a.shades);
    }
    p.arrays = v;
  }
  return p;
}

scene from_internal(const scene_params& p) {
  scene s;
  const camera_params& c = p.camera;
  s.cam.aspect = c.aspect_ratio;
  s.cam.width = c.image_width;
  s.cam.height = c.image_height;
  s.cam.viewport_height = c.viewport_height;
  s.cam.focal_length = c.focal_length;
  s.cam.lookfrom = from_internal(c.origin);
  if (c.lookat) s.cam.lookat = from_internal(*c.lookat);
  s.cam.vup = from_internal(c.vup);
  s.cam.vfov = c.vfov_degrees;
  s.cam.projection = projection(uint8_t(c.proj));
  s.sky.bottom = from_internal(p.sky.bottom);
  s.sky.top = from_internal(p.sky.top);
  if (p.light.direction) s.light.direction = from_internal(*p.light.direction);
  s.light.shadows = p.light.shadows;
  s.light.ao_samples = p.light.ao_samples;
  s.light.ao_distance = p.light.ao_distance;
  s.spheres.reserve(p.spheres.size());
  for (const raycast::sphere& b : p.spheres)
    s.spheres.push_back(sphere{from_internal(b.center), b.radius, from_internal(b.shade), from_internal(b.flat_color)});
  if (p.arrays) {
    const sphere_view& v = *p.arrays;
    sphere_arrays a;
    a.count = v.count;
    a.centers = from_internal(v.centers);
    a.radii = from_internal(v.radii);
    if (v.colors.data) a.colors = from_internal(v.colors);
    a.shade = from_internal(v.shade);
    a.owner = v.owner;  // a view's per-sphere shades are a caller's: none come back this way
    s.arrays = a;
  }
  return s;
}

// A name the input table's row accepts (the command line's parser and message).
std::string_view checked_name(setting_id id, const std::string& text) {
  const setting& row = input_row(id);
  size_t k = 0;
  if (auto e = parse_name(text, row.names, k, row.any_case)) invalid(std::string(row.keyword), *e);
  return row.names[k];
}

// A number within the input table's row's range (the command line's message).
void check_number(setting_id id, int64_t n) {
  const setting& row = input_row(id);
  given g;
  g.v.integer = n;
  g.tokens[0] = std::to_string(n);
  if (auto e = check_range(row, g)) invalid(std::string(row.keyword), *e);
}

render_options to_internal(const options& o) {
  render_options r;
  const backend b = *parse_backend(checked_name(setting_id::backend, o.backend));
  if (auto why = backend_unavailable(b)) throw error(error::kind::unsupported_backend, "backend", *why);
  r.which = b;
  r.prec = *parse_precision(checked_name(setting_id::precision, o.precision));
  check_number(setting_id::threads, o.threads);
  r.threads = o.threads;
  check_number(setting_id::samples, o.samples);
  r.samples = uint32_t(o.samples);
  r.sampler = *parse_sampler(checked_name(setting_id::sampler, o.sampler));
  r.seed = o.seed;
  return r;
}

pixel_rect region_of(const options& o, const raycast::camera& cam) {
  if (!o.region) return {0, 0, cam.image_width, cam.image_height};
  const struct region& g = *o.region;
  const std::string got = std::to_string(g.x0) + "," + std::to_string(g.y0) + "," + std::to_string(g.x1) + "," +
                          std::to_string(g.y1);
  if (auto why = check_region({g.x0, g.y0, g.x1, g.y1}, cam.image_width, cam.image_height, got))
    invalid("region", *why);
  return {g.x0, g.y0, g.x1, g.y1};
}

pixel_format internal(pixel_type t) { return t == pixel_type::rgb8 ? pixel_format::rgb8 : pixel_format::rgb_f32; }

io::file_format file_format_for(const std::string& path, const std::string& format) {
  io::file_format f{};
  if (path.empty()) invalid("path", "empty file name");
  if (!format.empty()) f = *io::format_from_name(checked_name(setting_id::format, format));
  else if (auto why = io::format_from_path(path, f)) invalid("path", *why);
  if (path == "-")
    if (auto why = io::stdout_format_error(f)) invalid("format", *why);
  return f;
}

void check_sides(io::file_format f, int64_t w, int64_t h) {
  if (const int64_t side = io::max_side(f); side > 0 && std::max(w, h) > side)
    invalid("format", std::string(io::display_name(f)) + " supports at most " + std::to_string(side) +
                          " pixels per side, got " + std::to_string(std::max(w, h)));
}

// io_error names the file first: "out.png: Permission denied".
[[noreturn]] void rethrow_io(const io::io_error& e) { throw error(error::kind::io, "path", e.what()); }

void find_installed_module() {
#ifdef RAYCAST_INSTALLED_MODULE_DIR
  io::add_image_module_dir(RAYCAST_INSTALLED_MODULE_DIR);
#endif
}

// The particle options as the command line's settings, each checked by its row.
settings particle_layer(const particles& p) {
  settings s;
  const auto set = [&s](setting_id id, const std::string& text) {
    const setting& row = input_row(id);
    given g;
    g.source = row.keyword;
    if (auto e = parse_value(row, text, g)) invalid(std::string(row.keyword), *e);
    if (auto e = check_range(row, g)) invalid(std::string(row.keyword), *e);
    s[id] = std::move(g);
  };
  const auto number = [](double x) {
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
    return std::string(buf, end);
  };
  if (p.radius) set(setting_id::radius, number(*p.radius));
  if (!p.color_by.empty()) set(setting_id::color_by, p.color_by);
  if (!p.colormap.empty()) set(setting_id::colormap, p.colormap);
  if (p.color_range) set(setting_id::color_range, number((*p.color_range)[0]) + "," + number((*p.color_range)[1]));
  return s;
}

}  // namespace

scene builtin_scene(const std::string& name) {
  auto spheres = builtin_spheres(name);
  if (!spheres) invalid("scene", not_one_of(name, quote_token(name), raycast::builtin_scene_names()));
  scene_params p;
  p.spheres = std::move(*spheres);
  return from_internal(p);
}

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> r;
  for (std::string_view n : raycast::builtin_scene_names()) r.emplace_back(n);
  return r;
}

scene load_scene(const std::string& path, const particles& p) {
  const particle_settings ps = particles_of(particle_layer(p), path, true);
  if (ps.refused) invalid(std::string(ps.refused->keyword), ps.why);
  if (is_ply_file_name(path)) {
    auto read = read_ply_file(path, ps.options);
    if (auto* e = std::get_if<scene_file_error>(&read))
      throw error(e->io ? error::kind::io : error::kind::invalid_argument, e->path, path + ": " + e->message);
    return from_internal(std::get<scene_file_contents>(read).scene);
  }
  auto parsed = load_scene_file(path);
  if (auto* e = std::get_if<scene_file_error>(&parsed))
    throw error(e->io ? error::kind::io : error::kind::invalid_argument, e->path, path + ": " + e->message);
  return from_internal(std::get<scene_params>(parsed));
}

scene parse_scene(const std::string& json_text) {
  auto parsed = parse_scene_file(json_text);
  if (auto* e = std::get_if<scene_file_error>(&parsed)) invalid(e->path, e->message);
  return from_internal(std::get<scene_params>(parsed));
}

scene scene_with(const std::string& kind, const std::string& source, const settings& over) {
  scene_file_contents c;
  // A file's errors, and its values' refused below, name it first.
  const std::string file = kind == "name" && is_scene_file_name(source) ? source + ": " : "";
  const particle_settings particles = particles_of(over, kind == "name" ? source : "", true);
  if (particles.refused) invalid(std::string(particles.refused->keyword), particles.why);
  if (kind == "json" || kind == "name") {
    auto read = kind == "name" ? read_scene(source, particles.options) : read_scene_text(source);
    if (auto* e = std::get_if<scene_file_error>(&read))
      throw error(e->io ? error::kind::io : error::kind::invalid_argument, e->path.empty() ? "scene" : e->path,
                  file + e->message);
    c = std::move(std::get<scene_file_contents>(read));
  }
  settings merged = c.keys;
  merge(merged, over, scene_settings());
  if (auto e = resolve(merged, c.scene.camera, c.scene.sky, c.scene.light)) {
    const bool from_file = e->row && merged.has(e->row->id) && !merged[e->row->id]->where.empty();
    invalid(e->source, (from_file ? file : "") + e->message);
  }
  // The scene's own rules (a lookat at lookfrom, ...), checked here where
  // who set each value is known; job() checks the spheres.
  const scene_params& p = c.scene;
  for (auto e : {validate(p.camera), validate(p.sky), validate(p.light)})
    if (e) invalid(path(*e), (blame(*e, merged, !file.empty()).from_file ? file : "") + e->message);
  return from_internal(c.scene);
}

struct job::impl {
  std::optional<renderer> r;
  pixel_rect region;
};

job::job(const scene& s, const options& o) : p_(std::make_unique<impl>()) {
  const scene_params params = to_internal(s);
  if (auto e = validate(params)) invalid(path(*e), e->message);
  const render_options ro = to_internal(o);
  const raycast::scene sc = make_scene(params);
  p_->region = region_of(o, sc.cam);
  try {
    p_->r.emplace(sc, ro);
  } catch (const unsupported_backend& e) {
    throw error(error::kind::unsupported_backend, "backend", e.what());
  }
}

job::~job() = default;
job::job(job&&) noexcept = default;
job& job::operator=(job&&) noexcept = default;

int64_t job::width() const { return p_->region.width(); }
int64_t job::height() const { return p_->region.height(); }
std::string job::backend() const { return std::string(to_string(p_->r->selected())); }

void job::render_into(void* data, size_t stride, pixel_type pixels) const {
  const pixel_rect& g = p_->region;
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

void job::write(const std::string& path, const std::string& format) const {
  const io::file_format f = file_format_for(path, format);
  check_sides(f, width(), height());
  find_installed_module();
  try {
    auto sink = io::open_sink(path, f, width(), height());
    render_to_sink(*p_->r, p_->region, io::pixel_format_for(f), *sink, path);
  } catch (const io::io_error& e) {
    rethrow_io(e);
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
    rethrow_io(e);
  }
}

void write(const std::string& path, const image& img, const std::string& format) {
  write(path, img.data.data(), img.stride(), img.width, img.height, img.pixels, format);
}

}  // namespace raycast::api
