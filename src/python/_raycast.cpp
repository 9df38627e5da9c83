// The Python module's C++ half, _raycast: raycast/raycast.h for NumPy.
// raycast/__init__.py turns Python's arguments into these calls (scene
// sources, dtypes, docstrings); this side checks shapes, reads the arrays in
// place and renders with the GIL released.
#include <dlfcn.h>

#include <array>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "formats/registry.h"
#include "particles/colormap.h"
#include "particles/elements.h"
#include "io/module/module_loader.h"
#include "library/pipeline.h"
#include "library/source.h"
#include "python/arrays.h"
#include "raycast/raycast.h"
#include "text/names.h"
#include "settings/table.h"

namespace py = pybind11;
namespace rc = raycast::api;

namespace {

using raycast::python::column_of;
using raycast::python::value_error;
using raycast::python::wrong_type;

// The address the last render read centres from: the tests' proof that an
// array was used in place.
const void* last_centers = nullptr;

// A name from a list (shade, dtype), refused in the input table's words.
size_t one_of(const char* field, const std::string& got, std::initializer_list<std::string_view> names) {
  size_t k = 0;
  for (std::string_view n : names) {
    if (n == got) return k;
    ++k;
  }
  value_error(field, raycast::not_one_of(got, raycast::quote_token(got), {names.begin(), names.size()}));
}

// The keywords (text, as the command line spells them), each parsed by its
// input table row's parser into a layer of settings, as the command line's
// options are: the camera, sky and light rows are range-checked after they
// are merged over the scene's keys (errors name the scene file's key,
// "camera.vfov"), the others here (errors name the keyword, "samples").
raycast::settings parse_keywords(const std::map<std::string, std::string>& keywords) {
  raycast::settings layer;
  for (const auto& [keyword, text] : keywords) {
    const raycast::setting* row = raycast::find_keyword(keyword);
    if (!row || row->id == raycast::setting_id::format || row->id == raycast::setting_id::output)
      value_error(keyword, "is not a render() keyword");
    raycast::given g;
    const std::string source = raycast::is_scene_row(*row) ? std::string(row->file_key) : keyword;
    if (auto e = raycast::parse_given(*row, text, source, g)) value_error(source, *e);
    if (!raycast::is_scene_row(*row))
      if (auto e = raycast::check_range(*row, g.v, g.tokens)) value_error(source, *e);
    layer[row->id] = std::move(g);
  }
  if (auto e = raycast::check_groups(layer)) value_error(e->source, e->message);
  return layer;
}

// Particle data as arrays (raycast/__init__.py's dict: centers, and
// radii, colors, color_by, types with type_names, a cell where given),
// read in place, as one frame.
raycast::particle_frame frame_of(const py::dict& d) {
  raycast::particle_frame f;
  size_t n = size_t(-1);
  const auto array = [&](const char* key) -> std::optional<py::array> {
    if (!d.contains(key) || d[key].is_none()) return std::nullopt;
    return d[key].cast<py::array>();
  };
  f.positions = column_of(*array("centers"), "centers", 3, n);
  f.count = n;
  if (auto a = array("radii")) f.radii = column_of(*a, "radii", 1, n);
  if (auto a = array("colors")) f.colors = column_of(*a, "colors", 3, n, true);
  if (auto a = array("color_by")) f.properties.push_back({"color_by", column_of(*a, "color_by", 1, n)});
  if (auto a = array("types")) {
    f.types = column_of(*a, "types", 1, n, false, true);
    f.type_names = d["type_names"].cast<std::vector<std::string>>();
  }
  if (d.contains("cell") && !d["cell"].is_none()) {
    const auto v = [](py::handle h) { const auto t = h.cast<std::array<double, 3>>(); return rc::vec3{t[0], t[1], t[2]}; };
    const py::tuple c = d["cell"].cast<py::tuple>();  // origin, a, b, c
    f.cell = raycast::particle_cell{v(c[0]), v(c[1]), v(c[2]), v(c[3]), {}};
  }
  last_centers = f.positions.data;
  return f;
}

// A scene source's frame `frame` (none: its first), or the sky.
raycast::described_scene source_frame(const std::string& kind, const std::string& source, std::optional<int64_t> frame,
                                      const raycast::settings& layer) {
  using raycast::front_end;
  last_centers = nullptr;
  raycast::scene_source src = kind == "json" ? raycast::scene_source::from_text(source, layer, front_end::library)
                              : kind == "name" ? raycast::scene_source(source, layer, front_end::library)
                                               : raycast::scene_source(std::nullopt, layer, front_end::library);
  if (!frame) return src.frame(0);
  if (!src.trajectory()) value_error("frame", "applies to a particle file's frames (this scene is one picture)");
  raycast::value v;
  v.first = *frame;
  std::vector<size_t> k;
  if (auto e = raycast::select_frames(v, src.frame_count(), k)) value_error("frame", *e);
  return src.frame(k[0]);
}

// The arrays' particles as a scene, under the camera and sky keys of a scene
// given with them (which must have no spheres of its own).
rc::scene arrays_scene(const std::string& kind, const std::string& source, const py::dict& particles,
                       const raycast::settings& layer) {
  raycast::settings over = layer;
  if (!kind.empty()) {
    raycast::scene_source src = kind == "json"
                                    ? raycast::scene_source::from_text(source, {}, raycast::front_end::library)
                                    : raycast::scene_source(source, {}, raycast::front_end::library);
    if (src.trajectory() || src.frame(0).scene.sphere_count() > 0)
      value_error("centers", "the scene has spheres already; give a scene without");
    over = src.keys();
    raycast::merge(over, layer);
  }
  return raycast::describe_particles(frame_of(particles), over, raycast::front_end::library,
                                     particles["framed"].cast<bool>())
      .scene;
}

py::array render_image(const std::string& kind, const std::string& source, std::optional<int64_t> frame,
                       std::optional<py::dict> particles, const std::map<std::string, std::string>& keywords,
                       const std::string& dtype) try {
  const raycast::settings layer = parse_keywords(keywords);
  raycast::run_settings run;
  if (auto e = raycast::resolve_run(layer, run)) throw raycast::library_error(raycast::refused(*e));
  const rc::pixel_type px = one_of("dtype", dtype, {"uint8", "float32"}) == 0 ? rc::pixel_type::rgb8
                                                                              : rc::pixel_type::rgb_f32;
  rc::scene s = particles ? arrays_scene(kind, source, *particles, layer) : source_frame(kind, source, frame, layer).scene;
  std::optional<rc::job> j;
  {
    py::gil_scoped_release free;  // preparing 10^6 spheres takes a while too
    j.emplace(std::move(s), run.options);
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
} catch (const raycast::refusal& r) {
  throw raycast::library_error(r);
}

// A particle file's frames, for raycast.frames(): each read on demand.
class trajectory {
 public:
  explicit trajectory(const std::string& path) try : path_(path) {
    const raycast::formats::detected f = raycast::formats::detect(path);
    if (!f.particles) value_error("path", path + ": is not a particle file (a LAMMPS dump, extended XYZ, GSD or PLY file)");
    t_ = f.particles->open(path);
    count_ = t_->frame_count();
  } catch (const raycast::formats::format_error& e) {
    throw rc::error(e.io ? rc::error::kind::io : rc::error::kind::invalid_argument, "path", path + ": " + e.what());
  }
  size_t size() const { return count_; }
  py::dict read(int64_t k) try {
    raycast::value v;
    v.first = k;
    std::vector<size_t> at;
    if (auto e = raycast::select_frames(v, count_, at)) value_error("frame", *e);
    raycast::formats::wanted_columns all;
    all.all = true;
    raycast::particle_frame f;
    {
      py::gil_scoped_release free;
      f = t_->read(at[0], all);
    }
    return raycast::python::frame_dict(f);
  } catch (const raycast::formats::format_error& e) {
    throw rc::error(e.io ? rc::error::kind::io : rc::error::kind::invalid_argument, "path", path_ + ": " + e.what());
  }

 private:
  std::string path_;
  std::unique_ptr<raycast::formats::trajectory> t_;
  size_t count_ = 0;
};

void write_image(const std::string& path, const py::array& image, const std::string& format) {
  if (image.ndim() != 3 || image.shape(2) != 3) value_error("image", "must have shape (H, W, 3)");
  rc::pixel_type px;
  if (image.dtype().is(py::dtype::of<uint8_t>())) px = rc::pixel_type::rgb8;
  else if (image.dtype().is(py::dtype::of<float>())) px = rc::pixel_type::rgb_f32;
  else throw wrong_type{"image", "want a uint8 or float32 array"};
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

// The input table as Python values.
py::list input_table() {
  static constexpr const char* types[] = {"integer", "real",     "aspect",   "triple", "name", "region",
                                          "seed",    "text",     "flag",     "interval", "type_map", "frames"};
  py::list rows;
  for (const raycast::setting& r : raycast::input_table()) {
    py::dict row;
    row["keyword"] = std::string(r.keyword);
    row["option"] = std::string(r.option);
    row["file_key"] = std::string(r.file_key);
    row["type"] = types[size_t(r.type)];
    py::list names;
    for (std::string_view n : r.names) names.append(std::string(n));
    row["names"] = names;
    rows.append(row);
  }
  return rows;
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
    } catch (const wrong_type& e) {
      py::object ex = py::reinterpret_borrow<py::object>(PyExc_TypeError)(e.field + ": " + e.message);
      ex.attr("field") = e.field;
      ex.attr("message") = e.message;
      ex.attr("kind") = "invalid_argument";
      PyErr_SetObject(PyExc_TypeError, ex.ptr());
    }
  });
  m.def("render", &render_image);
  py::class_<trajectory>(m, "trajectory")
      .def(py::init<const std::string&>())
      .def("__len__", &trajectory::size)
      .def("read", &trajectory::read, "Frame k's arrays (negative: from the end), viewing the file's memory.");
  m.def("write", &write_image, py::arg("path"), py::arg("image"), py::arg("format") = "");
  m.def("builtin_scene_names", &rc::builtin_scene_names);
  m.def("element_symbol", [](int z) { return std::string(raycast::element_symbol(z)); });
  m.def("_element_style", [](const std::string& symbol) -> py::object {
    const raycast::element_style* e = raycast::element_named(symbol);
    if (!e) return py::none();
    return py::make_tuple(e->radius, py::make_tuple(e->color[0], e->color[1], e->color[2]));
  }, "The radius and colour the tables give an element (for the tables' tests).");
  m.def("_colormap_color", [](const std::string& name, double t) {
    const auto c = raycast::colormap_color(raycast::colormap_named(name), t, 0.0, 1.0);
    return py::make_tuple(c[0], c[1], c[2]);
  }, "A colormap's colour at t in [0, 1] (for the tables' tests).");
  m.def("input_table", &input_table,
        "The input table's rows (keyword, option, file_key, type, names): what the keywords, the command line's "
        "options and the scene file's keys are, for docstrings and tests.");
  m.def("_last_centers_address", [] { return reinterpret_cast<uintptr_t>(last_centers); },
        "The address of the centres the last render read (0: none): for tests of the no-copy path.");
}
