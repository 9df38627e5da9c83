// NumPy arrays as the library's columns (raycast/description.h), read in
// place, and columns as NumPy arrays viewing memory a capsule keeps alive:
// the Python module's two directions, no copy either way where the layout
// allows (a column of another byte order is a NumPy dtype of that order).
#pragma once
#include <cstddef>
#include <memory>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "raycast/description.h"
#include "scene/particles.h"

namespace raycast::python {

namespace py = pybind11;

// A value of the wrong type: TypeError, with .field and .message as ValueError's.
struct wrong_type {
  std::string field, message;
};
[[noreturn]] void value_error(const std::string& field, const std::string& message);

// a as a column of `components` values a row (1: shape (N,), else (N, components)),
// its rows checked against count (size_t(-1): any, and set). Floats of 32 or 64
// bits; with `colours`, uint8 too (read as value / 255); with `integers`,
// 32-bit integers (types).
api::column column_of(const py::array& a, const char* name, int components, size_t& count, bool colours = false,
                      bool integers = false);

// The frame's column as an array (count rows, `components` a row) viewing
// its memory, which `owner` keeps alive.
py::array array_of(const api::column& c, size_t count, int components, const std::shared_ptr<const void>& owner);

// A frame's arrays as a dict: positions, and radii, colors, types,
// type_names, cell (origin, a, b, c, pbc), timestep and each property
// where the frame has them.
py::dict frame_dict(const particle_frame& f);

}  // namespace raycast::python
