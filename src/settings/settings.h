// The input table: every setting a user can give -- a command-line option, a
// scene file's camera, sky, light or ambient_occlusion key, a Python keyword -- declared once, with its
// value type, range, default and help. The command line (cli/options.cpp)
// builds its options and --help from it, the scene file reader
// (scene_file.cpp) its camera and sky keys, the Python module its keywords.
//
// One parser per value type, shared by all three: a size, a number in a
// range, an aspect ("16:9" or 1.7778), x,y,z, a name from a list, a region,
// a seed. Each source parses its own text into a settings layer (syntax
// only); layers merge (the command line over the file); then resolve()
// checks the ranges of what won and computes the derived settings (the
// camera's lookat from vup, the height from width and aspect) from the
// merged values only.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "scene/camera.h"
#include "scene/light.h"
#include "scene/sky.h"

namespace raycast {

enum class value_type : uint8_t {
  integer,  // a whole number: 400
  real,     // a finite number: 1.5, -2e3
  aspect,   // W:H or a number: 16:9, 1.7778
  triple,   // x,y,z on the command line, [x, y, z] in a scene file
  name,     // one of setting::names
  region,   // x0,y0,x1,y1 (its bounds depend on the image: checked by the caller)
  seed,     // 0 to 2^64 - 1
  text,     // any text: a file name
  flag,     // present or not; no value
  interval, // lo,hi: two finite numbers, lo below hi (value::triple's first two)
};

// Every setting, scene keys first. A layer holds at most one value of each.
enum class setting_id : uint8_t {
  width,
  height,
  aspect,
  vfov,
  viewport_height,
  focal_length,
  projection,
  origin,    // the command line's other name for lookfrom
  lookfrom,
  lookat,
  vup,
  sky_bottom,
  sky_top,
  light,
  shadows,
  ao,
  ao_distance,
  // The run's options: the command line's and the library's, not a scene's.
  output,
  scene,
  format,
  backend,
  precision,
  threads,
  samples,
  sampler,
  seed,
  region,
  radius,       // a particle file's: every sphere's radius
  color_by,     // a particle file's vertex property shown in colour
  colormap,
  color_range,
  quiet,
  stats,
  version,
};
inline constexpr size_t setting_count = size_t(setting_id::version) + 1;
inline constexpr size_t scene_setting_count = size_t(setting_id::ao_distance) + 1;

// Where a number (or each component of a triple) may lie.
struct value_range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;  // open: the bound itself is refused
};

struct setting {
  setting_id id;
  std::string_view option;        // "--width": the command line's long name
  std::string_view short_option;  // "-w", or ""
  std::string_view file_key;      // "camera.width", or "": not in scene files
  std::string_view keyword;       // the Python keyword, or ""
  value_type type;
  value_range range;
  std::span<const std::string_view> names;  // value_type::name: what it accepts
  std::string_view type_name;     // "N", "X,Y,Z": --help's placeholder
  std::string_view default_text;  // --help's [default]
  std::string_view help;
  // Settings of one group name the same thing two ways (vfov or
  // viewport_height, origin or lookfrom): one source gives one of them, and
  // a later source's replaces an earlier source's.
  uint8_t group = 0;
  bool any_case = false;  // value_type::name: "PNG" is "png"
};

// The scene's rows (camera and sky), in the table's order; the run's rows
// follow in the full table (settings/inputs.h).
std::span<const setting> scene_settings();
const setting* find_file_key(std::string_view file_key);

// A parsed value: the member its type uses.
struct value {
  int64_t integer = 0;
  double real = 0;  // real, aspect
  vec3 triple{0.0};
  size_t name = 0;  // index into setting::names
  std::array<int64_t, 4> region{};
  uint64_t seed = 0;
  std::string text;
  bool flag = false;
};

// A value as one source gave it: the token as typed (each component's, for a
// triple; cut short for messages) and who gave it, for messages that blame it.
struct given {
  value v;
  std::array<std::string, 3> tokens;
  std::string source;  // the option as typed ("--origin"), or the scene file's key
  std::string where;   // a scene file's " (at line L, column C: excerpt)"; else ""
};

// One source's settings (or several merged).
struct settings {
  std::array<std::optional<given>, setting_count> at;
  std::optional<given>& operator[](setting_id id) { return at[size_t(id)]; }
  const std::optional<given>& operator[](setting_id id) const { return at[size_t(id)]; }
  bool has(setting_id id) const { return at[size_t(id)].has_value(); }
};

// A setting refused: which one and why, in the user's terms ("'0' is too
// small (at least 1)"); given.source names who gave it.
struct setting_error {
  const setting* row = nullptr;
  std::string source;   // "--width", "camera.width"
  std::string message;  // why, with a scene file's place appended
};

// The token in quotes, at most 32 bytes of it (cut at a character boundary,
// "…" when cut): messages never carry a huge token whole.
std::string quote_token(std::string_view token);

// The parsers, one per type; each returns why the text is not a value.
// A number beyond the type's range sets *beyond (where given) and value to
// the nearest the type has (the int64 bound, an infinity, a zero); the message
// says too small, too large or too near 0.
std::optional<std::string> parse_int(std::string_view text, int64_t& value, bool* beyond = nullptr);
std::optional<std::string> parse_real(std::string_view text, double& value, bool* beyond = nullptr);
std::optional<std::string> parse_aspect(std::string_view text, double& value);
std::optional<std::string> parse_triple(std::string_view text, vec3& value, std::array<std::string, 3>* tokens = nullptr);
std::optional<std::string> parse_seed(std::string_view text, uint64_t& value);
std::optional<std::string> parse_region(std::string_view text, std::array<int64_t, 4>& value);
std::optional<std::string> parse_name(std::string_view text, std::span<const std::string_view> names, size_t& index,
                                      bool any_case = false);

// Parses text as row's type into g (g.v, g.tokens); the range is checked later.
std::optional<std::string> parse_value(const setting& row, std::string_view text, given& g);

// Why a value is outside row's range ("'0' is too small (at least 1)"), or nullopt.
std::optional<std::string> check_range(const setting& row, const given& g);

// Why the region r (x0, y0, x1, y1; token: as the user gave it) is not a
// window of a width x height image, or nullopt: its bounds depend on the
// image, so the caller checks them once the image is known.
std::optional<std::string> check_region(const std::array<int64_t, 4>& r, int64_t width, int64_t height,
                                        std::string_view token);

// Two settings of one group in one source: the error blaming the later row.
std::optional<setting_error> check_groups(std::span<const setting> table, const settings& s);

// over on top of base: each value over gives replaces base's, and one of a
// group replaces the whole group.
void merge(settings& base, const settings& over, std::span<const setting> table);

// The merged scene settings applied to a camera, sky and lighting (defaults
// where not given), ranges checked, derived settings computed: a vup without
// a lookat looks down -z from the merged lookfrom. The camera's and the
// lighting's own rules (validate()) are the caller's to check after.
std::optional<setting_error> resolve(const settings& s, camera_params& cp, sky& sk, lighting& li);

}  // namespace raycast
