// A text frame's decoded numbers: `slots` arrays of `rows` doubles each (a
// slot is one value of a row: x, y, z, a radius, one component of a
// property), slot-major so that a column is contiguous, and each row's type
// index. The arrays hold as many rows as the header promises and the rest of
// the file can hold (input::text_trajectory::capacity), left uninitialized:
// only the rows the file really holds are ever written, so memory is what
// was read.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "memory/arrays.h"
#include "raycast/description.h"
#include "scene/particles.h"

namespace raycast::formats::input {

// The arrays are the memory room's filled_later_array (memory/arrays.h):
// written whole before they are read, in the page size that costs less here.
struct table {
  table(size_t rows_, size_t slots_, bool typed)
      : rows(rows_), slots(slots_), values(rows_ * slots_), types(typed ? rows_ : 0) {}
  size_t rows, slots;
  filled_later_array<double> values;
  filled_later_array<uint32_t> types;

  double* slot(size_t s) const { return const_cast<double*>(values.data()) + s * rows; }
  // Slots s .. s + components - 1 as one column.
  api::column column(size_t s) const {
    return {slot(s), api::element::f64, sizeof(double), std::ptrdiff_t(rows * sizeof(double))};
  }
  api::column type_column() const { return api::packed(types.data()); }
};

// Type names in the order first seen (element symbols, XYZ species): the
// few a file has by a look along them, a hostile file's many by a hash.
class type_namer {
 public:
  explicit type_namer(std::vector<std::string>& names) : names_(names) {}
  uint32_t index(std::string_view name) {
    if (last_ < names_.size() && names_[last_] == name) return uint32_t(last_);
    if (names_.size() <= 16) {
      for (size_t k = 0; k < names_.size(); ++k)
        if (names_[k] == name) return uint32_t(last_ = k);
    } else if (auto it = many_.find(std::string(name)); it != many_.end()) {
      return uint32_t(last_ = it->second);
    }
    names_.emplace_back(name);
    if (names_.size() > 16) {
      if (many_.empty())
        for (size_t k = 0; k < names_.size(); ++k) many_.emplace(names_[k], k);
      else
        many_.emplace(names_.back(), names_.size() - 1);
    }
    return uint32_t(last_ = names_.size() - 1);
  }

 private:
  std::vector<std::string>& names_;
  std::unordered_map<std::string, size_t> many_;
  size_t last_ = 0;
};

// The frame of a table: positions from slots 0, 1, 2; the owner keeps it.
inline particle_frame frame_of(std::shared_ptr<const table> t) {
  particle_frame f;
  f.count = t->rows;
  f.positions = t->column(0);
  if (!t->types.empty()) f.types = t->type_column();
  f.owner = std::move(t);
  return f;
}

}  // namespace raycast::formats::input
