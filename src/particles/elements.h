// The chemical elements as particle pictures draw them: the van der Waals
// radius (Alvarez 2013) and Jmol's colour, by symbol; and the palette of
// types that name no element (numbered types: LAMMPS's 1, 2, ...).
#pragma once
#include <array>
#include <cstddef>
#include <string_view>

namespace raycast {

struct element_style {
  std::string_view symbol;  // "H", "He", ... "Og"
  float radius;             // angstrom; default_element_radius where the table gives none
  std::array<float, 3> color;  // in [0, 1]; default_type_color past Jmol's table
};

// The element a type name is, as files spell it ("Cu"; also "CU", "cu"), or
// null where the name is no element's symbol.
const element_style* element_named(std::string_view name);
// Element Z's symbol (1: "H", ... 118: "Og"), or "" outside them.
std::string_view element_symbol(int z);

inline constexpr float default_element_radius = 2.0f;    // where Alvarez gives none
inline constexpr float default_type_radius = 0.5f;       // types that are no element: touching at a spacing of 1
inline constexpr std::array<float, 3> default_type_color = {0.6f, 0.6f, 0.6f};

// Type k's colour where types are no elements: matplotlib's tab10 cycle
// (Tableau's ten), k mod 10.
std::array<float, 3> palette_color(size_t k);

}  // namespace raycast
