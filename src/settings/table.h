// The input table: every setting a user can give -- a command-line option,
// a scene file's key, a Python keyword -- declared once, with its value type,
// range, default and help. The command line builds its options and --help
// from it, the scene file reader its camera, sky and light keys, the Python
// module its keywords; resolve.h turns the values given into the description
// of a render (raycast/description.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

namespace raycast {

enum class value_type : uint8_t {
  integer,   // a whole number: 400
  real,      // a finite number: 1.5, -2e3
  aspect,    // W:H or a number: 16:9, 1.7778
  triple,    // x,y,z on the command line, [x, y, z] in a scene file
  name,      // one of setting::names
  region,    // x0,y0,x1,y1 (its bounds depend on the image: checked once it is known)
  seed,      // 0 to 2^64 - 1
  text,      // any text: a file name
  flag,      // present or not; no value
  interval,  // lo,hi: two finite numbers, lo below hi; or pLO,pHI: percentiles, 0 <= LO < HI <= 100
  type_map,  // NAME=VALUE,NAME=VALUE: a number or a colour (#rrggbb) a type
  frames,    // K or A:B[:S], Python's index and slice rules
};

// Every setting: the scene's first (a scene file's keys too), then the run's.
enum class setting_id : uint8_t {
  width,
  height,
  aspect,
  vfov,
  viewport_height,
  focal_length,
  projection,
  origin,  // the command line's other name for lookfrom
  lookfrom,
  lookat,
  vup,
  sky_bottom,
  sky_top,
  light,
  shadows,
  ao,
  ao_distance,
  // How particle data become spheres.
  radius,
  type_radius,
  type_color,
  color_by,
  colormap,
  color_range,
  shade,
  view,
  // The run's.
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
  frames,
  fps,
  skip_existing,
  quiet,
  stats,
  version,
};
inline constexpr size_t setting_count = size_t(setting_id::version) + 1;

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
  std::string_view keyword;       // the Python keyword and the library's field name, or ""
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

std::span<const setting> input_table();
const setting& input_row(setting_id id);
// The row of a scene file's key ("camera.vfov") or a keyword ("vfov"), or null.
const setting* find_file_key(std::string_view file_key);
const setting* find_keyword(std::string_view keyword);

// Whether a row belongs to the scene (a scene file may give it) or says how
// particle data become spheres.
inline bool is_scene_row(const setting& row) { return !row.file_key.empty(); }
inline bool is_particle_row(setting_id id) { return id >= setting_id::radius && id <= setting_id::view; }

}  // namespace raycast
