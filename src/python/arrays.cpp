#include "python/arrays.h"

#include <pybind11/stl.h>

#include "raycast/raycast.h"

namespace raycast::python {

void value_error(const std::string& field, const std::string& message) {
  throw api::error(api::error::kind::invalid_argument, field, message);
}

api::column column_of(const py::array& a, const char* name, int components, size_t& count, bool colours,
                      bool integers) {
  const bool matrix = components > 1;
  if (a.ndim() != (matrix ? 2 : 1) || (matrix && a.shape(1) != components))
    value_error(name, matrix ? "must have shape (N, " + std::to_string(components) + ")" : "must have shape (N,)");
  if (count != size_t(-1) && size_t(a.shape(0)) != count)
    value_error(name, "has " + std::to_string(a.shape(0)) + " rows, want " + std::to_string(count) +
                          " (one per centre)");
  count = size_t(a.shape(0));
  api::column c;
  c.data = a.data();
  if (a.dtype().is(py::dtype::of<float>())) c.type = api::element::f32;
  else if (a.dtype().is(py::dtype::of<double>())) c.type = api::element::f64;
  else if (colours && a.dtype().is(py::dtype::of<uint8_t>())) c.type = api::element::u8;
  else if (integers && a.dtype().is(py::dtype::of<int32_t>())) c.type = api::element::i32;
  else if (integers && a.dtype().is(py::dtype::of<uint32_t>())) c.type = api::element::u32;
  else throw wrong_type{name, colours ? "want a float32, float64 or uint8 array" : "want a float32 or float64 array"};
  // Strides as NumPy has them: any layout is read in place, a zero stride too.
  c.stride = a.strides(0);
  c.component_stride = matrix ? a.strides(1) : 0;
  return c;
}

py::array array_of(const api::column& c, size_t count, int components, const std::shared_ptr<const void>& owner) {
  static constexpr const char* codes[] = {"f4", "f8", "u1", "u4", "i4"};  // api::element's order
  const std::string order = c.byte_swapped ? ">" : "=";  // swapped: big-endian data on this little-endian machine
  const py::dtype dt(order + codes[size_t(c.type)]);
  // The capsule holds a copy of the owner: the array keeps the frame's memory alive.
  auto* keep = new std::shared_ptr<const void>(owner);
  py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<const void>*>(p); });
  std::vector<py::ssize_t> shape{py::ssize_t(count)}, strides{c.stride};
  if (components > 1) shape.push_back(components), strides.push_back(c.component_stride);
  py::array a(dt, shape, strides, c.data, base);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;  // the file's memory
  return a;
}

py::dict frame_dict(const particle_frame& f) {
  py::dict d;
  d["positions"] = array_of(f.positions, f.count, 3, f.owner);
  if (f.radii) d["radii"] = array_of(*f.radii, f.count, 1, f.owner);
  if (f.colors) d["colors"] = array_of(*f.colors, f.count, 3, f.owner);
  if (f.types) {
    d["types"] = array_of(*f.types, f.count, 1, f.owner);
    d["type_names"] = f.type_names;
  }
  py::dict props;
  for (const particle_property& p : f.properties) props[py::str(p.name)] = array_of(p.values, f.count, p.components, f.owner);
  d["properties"] = props;
  if (f.cell) {
    const auto v = [](const api::vec3& x) { return py::make_tuple(x.x, x.y, x.z); };
    d["cell"] = py::dict(py::arg("origin") = v(f.cell->origin), py::arg("a") = v(f.cell->a), py::arg("b") = v(f.cell->b),
                         py::arg("c") = v(f.cell->c), py::arg("pbc") = py::make_tuple(f.cell->periodic[0],
                                                                                       f.cell->periodic[1],
                                                                                       f.cell->periodic[2]));
  }
  if (f.timestep) d["timestep"] = *f.timestep;
  return d;
}

}  // namespace raycast::python
