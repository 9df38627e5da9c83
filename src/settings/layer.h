// A layer of settings: the values one source gave (the command line, a scene
// file's keys, Python's keywords, a library caller's structs), each with who
// gave it, so that an error blames the source's own spelling ("--width",
// "camera.width", "width"). Layers merge, a later source over an earlier.
#pragma once
#include <array>
#include <optional>
#include <span>
#include <string>

#include "settings/table.h"
#include "settings/values.h"

namespace raycast {

struct given {
  value v;
  std::array<std::string, 3> tokens;  // each component as typed (cut short), for messages
  std::string source;  // the option as typed ("--origin"), the scene file's key, or the keyword
  std::string where;   // a scene file's " (at line L, column C: excerpt)"; else ""
};

struct settings {
  std::array<std::optional<given>, setting_count> at;
  std::optional<given>& operator[](setting_id id) { return at[size_t(id)]; }
  const std::optional<given>& operator[](setting_id id) const { return at[size_t(id)]; }
  bool has(setting_id id) const { return at[size_t(id)].has_value(); }
};

// A setting refused: which row and why, in the user's terms; source names who gave it.
struct setting_error {
  const setting* row = nullptr;
  std::string source;   // "--width", "camera.width", "width"
  std::string message;  // why, with a scene file's place appended
};

// Parses text as row's value, given by source: the value, or why not (its
// range is not checked here).
std::optional<std::string> parse_given(const setting& row, std::string_view text, std::string source, given& g);

// Two settings of one group in one source: the error blaming the later row.
std::optional<setting_error> check_groups(const settings& s);

// over on top of base: each value over gives replaces base's, and one of a
// group replaces the whole group.
void merge(settings& base, const settings& over);

}  // namespace raycast
