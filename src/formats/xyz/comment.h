// An extended XYZ frame's comment line: key=value pairs separated by blanks,
// a value bare, "double quoted" (backslash escapes), or in { } or [ ]; a key
// alone is a flag. Of them the reader takes Properties (the rows' columns),
// Lattice (the cell's edges), Origin, pbc and step / timestep.
//
//   Lattice="4.0 0.0 0.0 1.0 5.0 0.0 0.5 0.5 6.0" Properties=species:S:1:pos:R:3:forces:R:3 pbc="T T F"
//
// A comment that is not such pairs is a plain XYZ file's free text.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace raycast::formats::xyz {

using key_values = std::vector<std::pair<std::string, std::string>>;

// The pairs of a comment line, or nullopt when it is not key=value syntax.
std::optional<key_values> parse_key_values(std::string_view line);

// One entry of Properties=NAME:TYPE:COUNT:...; TYPE is S (string), R
// (real), I (integer) or L (logical, T or F).
struct property_spec {
  std::string name;
  char type = 'R';
  uint32_t count = 1;
};

// The entries of a Properties value, or a message why it is not one.
struct specs_result {
  std::vector<property_spec> specs;
  std::string error;
};
specs_result parse_properties(std::string_view value);

// A value's case-insensitive key lookup (extended XYZ keys are case-insensitive).
const std::string* find_key(const key_values& kv, std::string_view key);

}  // namespace raycast::formats::xyz
