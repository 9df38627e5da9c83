// The Python module's C++ half, _raycast: raycast/raycast.h for NumPy.
// raycast/__init__.py turns Python's arguments into these calls (scene
// sources, dtypes, docstrings); this side checks shapes, reads the arrays in
// place and renders with the GIL released.
#include <dlfcn.h>

#include <array>
#include <map>
#include <optional>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "io/module_loader.h"
#include "raycast/raycast.h"
#include "raycast/inputs.h"

namespace py = pybind11;
namespace rc = raycast::api;

namespace {

// The address the last render read centres from: the tests' proof that an
// array was used in place.
const void* last_centers = nullptr;

[[noreturn]] void value_error(const std::string& field, const std::string& message) {
  throw rc::error(rc::error::kind::invalid_argument, field, message);
}

rc::sphere_arrays::column column_of(const py::array& a, const char* name, size_t& count) {
  const bool matrix = std::string(name) != "radii";
  if (a.ndim() != (matrix ? 2 : 1) || (matrix && a.shape(1) != 3))
    value_error(name, matrix ? "must have shape (N, 3)" : "must have shape (N,)");
  if (count != size_t(-1) && size_t(a.shape(0)) != count)
    value_error(name, "has " + std::to_string(a.shape(0)) + " rows, want " + std::to_string(count) +
                          " (one per centre)");
  count = size_t(a.shape(0));
  rc::sphere_arrays::column c;
  c.data = a.data();
  if (a.dtype().is(py::dtype::of<float>())) c.type = rc::sphere_arrays::element::f32;
  else if (a.dtype().is(py::dtype::of<double>())) c.type = rc::sphere_arrays::element::f64;
  else throw py::type_error(std::string(name) + ": want a float32 or float64 array");
  // Strides as NumPy has them: any layout is read in place (a zero stride,
  // packed to the library, was made contiguous by __init__.py).
  c.stride = a.strides(0);
  c.component_stride = matrix ? a.strides(1) : 0;
  return c;
}

rc::shading shading_of(const std::string& s) {
  if (s == "normal") return rc::shading::normal;
  if (s == "flat") return rc::shading::flat;
  if (s == "lit") return rc::shading::lit;
  value_error("shade", "'" + s + "' is not one of normal, flat, lit");
}

// The camera, sky and light keywords (text, as the command line spells them),
// parsed by the input table's parsers into settings that override the
// scene's keys as the command line's options do; errors name the scene
// file's key ("camera.vfov").
raycast::settings keyword_settings(const std::map<std::string, std::string>& keywords) {
  raycast::settings layer;
  for (const auto& [keyword, text] : keywords) {
    const raycast::setting* row = nullptr;
    for (const raycast::setting& r : raycast::scene_settings())
      if (r.keyword == keyword) row = &r;
    if (!row) value_error(keyword, "is not a camera, sky or light keyword");
    raycast::given g;
    g.source = std::string(row->file_key);
    if (auto e = raycast::parse_value(*row, text, g)) value_error(g.source, *e);
    layer[row->id] = std::move(g);
  }
  if (auto e = raycast::check_groups(raycast::scene_settings(), layer)) value_error(e->source, e->message);
  return layer;
}

py::array render_image(const std::string& kind, const std::string& source, std::optional<py::array> centers,
                       std::optional<py::array> radii, std::optional<py::array> colors, const std::string& shade,
                       const std::map<std::string, std::string>& camera, const std::string& backend,
                       const std::string& precision, int threads, int64_t samples, const std::string& sampler,
                       uint64_t seed, std::optional<std::array<int64_t, 4>> region, const std::string& dtype) {
  rc::scene s = rc::scene_with(kind, source, keyword_settings(camera));

  const rc::shading sh = shading_of(shade);
  if (centers || radii || colors) {
    if (!centers || !radii) value_error(centers ? "radii" : "centers", "is required with centers/radii/colors");
    if (!s.spheres.empty()) value_error("centers", "the scene has spheres already; give a scene without");
    rc::sphere_arrays a;
    size_t n = size_t(-1);
    a.centers = column_of(*centers, "centers", n);
    a.radii = column_of(*radii, "radii", n);
    if (colors) a.colors = column_of(*colors, "colors", n);
    a.count = n;
    a.shade = sh;
    s.arrays = a;
    last_centers = a.centers.data;
  } else {
    last_centers = nullptr;
  }

  rc::options o;
  o.backend = backend;
  o.precision = precision;
  o.threads = threads;
  o.samples = samples;
  o.sampler = sampler;
  o.seed = seed;
  if (region) o.region = rc::region{(*region)[0], (*region)[1], (*region)[2], (*region)[3]};
  rc::pixel_type px;
  if (dtype == "uint8") px = rc::pixel_type::rgb8;
  else if (dtype == "float32") px = rc::pixel_type::rgb_f32;
  else value_error("dtype", "'" + dtype + "' is not one of uint8, float32");

  std::optional<rc::job> j;
  {
    py::gil_scoped_release free;  // preparing 10^6 spheres takes a while too
    j.emplace(s, o);
  }
  const std::vector<py::ssize_t> shape = {py::ssize_t(j->height()), py::ssize_t(j->width()), 3};
  py::array out = px == rc::pixel_type::rgb8 ? py::array(py::dtype::of<uint8_t>(), shape)
                                             : py::array(py::dtype::of<float>(), shape);
  void* data = out.mutable_data();
  const size_t stride = size_t(out.strides(0));
  {
    py::gil_scoped_release free;
    j->render_into(data, stride, px);
  }
  return out;
}

void write_image(const std::string& path, const py::array& image, const std::string& format) {
  if (image.ndim() != 3 || image.shape(2) != 3) value_error("image", "must have shape (H, W, 3)");
  rc::pixel_type px;
  if (image.dtype().is(py::dtype::of<uint8_t>())) px = rc::pixel_type::rgb8;
  else if (image.dtype().is(py::dtype::of<float>())) px = rc::pixel_type::rgb_f32;
  else throw py::type_error("image: want a uint8 or float32 array");
  const py::ssize_t item = image.itemsize();
  if (image.strides(2) != item || image.strides(1) != 3 * item || image.strides(0) < 3 * item * image.shape(1))
    value_error("image", "rows must be C-contiguous (numpy.ascontiguousarray)");
  const void* data = image.data();
  const size_t stride = size_t(image.strides(0));
  const int64_t w = image.shape(1), h = image.shape(0);
  py::gil_scoped_release free;
  rc::write(path, data, stride, w, h, px, format);
}

// Where the image module is: <prefix>/<libdir>/raycast for the installed
// package (relative to this file's folder), bin/ of the build tree for the
// build tree's.
void find_image_module() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&find_image_module), &info) && info.dli_fname) {
    const std::string self = info.dli_fname;
    raycast::io::add_image_module_dir(self.substr(0, self.find_last_of('/')) + "/" RAYCAST_PY_MODULE_RELDIR);
  }
  raycast::io::add_image_module_dir(RAYCAST_BUILD_MODULE_DIR);
}

}  // namespace

PYBIND11_MODULE(_raycast, m) {
  m.doc() = "raycast's C++ half; use the raycast package.";
  find_image_module();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const rc::error& e) {
      py::object type = e.kind() == rc::error::kind::io ? py::object(py::reinterpret_borrow<py::object>(PyExc_OSError))
                                                         : py::object(py::reinterpret_borrow<py::object>(PyExc_ValueError));
      py::object ex = type(e.what());
      ex.attr("field") = e.field();
      ex.attr("message") = e.message();
      ex.attr("kind") = e.kind() == rc::error::kind::io                    ? "io"
                        : e.kind() == rc::error::kind::unsupported_backend ? "unsupported_backend"
                                                                            : "invalid_argument";
      PyErr_SetObject(type.ptr(), ex.ptr());
    }
  });
  m.def("render", &render_image);
  m.def("write", &write_image, py::arg("path"), py::arg("image"), py::arg("format") = "");
  m.def("builtin_scene_names", &rc::builtin_scene_names);
  m.def("_last_centers_address", [] { return reinterpret_cast<uintptr_t>(last_centers); },
        "The address of the centres the last render read (0: none): for tests of the no-copy path.");
}
