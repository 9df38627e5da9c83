// The input table's value types, parsed: one parser per type, shared by
// every front end, so a value is spelled, range-checked and refused the
// same way on the command line, in a scene file and from Python.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "settings/table.h"
#include "text/quote.h"

namespace raycast {

// A parsed value: the member its type uses.
struct value {
  int64_t integer = 0;
  double real = 0;  // real, aspect
  std::array<double, 3> triple{};  // triple; interval: [0] and [1]
  size_t name = 0;  // index into setting::names
  std::array<int64_t, 4> region{};
  uint64_t seed = 0;
  std::string text;
  bool flag = false;  // a flag's; interval: in percentiles
  // type_map: each NAME=VALUE (a number in [0], or a colour's r g b in [0, 1]).
  std::vector<std::pair<std::string, std::array<double, 3>>> pairs;
  // frames: an index (step 0), or a slice start:stop:step, each end absent
  // where the text leaves it out (Python's rules, resolved once the count is known).
  std::optional<int64_t> first, last;
  int64_t step = 0;
};

// The parsers, one per type; each returns why the text is not a value.
// A number beyond the type's range sets *beyond (where given) and value to
// the nearest the type has (the int64 bound, an infinity, a zero); the
// message says too small, too large or too near 0.
std::optional<std::string> parse_int(std::string_view text, int64_t& value, bool* beyond = nullptr);
std::optional<std::string> parse_real(std::string_view text, double& value, bool* beyond = nullptr);
std::optional<std::string> parse_aspect(std::string_view text, double& value);
std::optional<std::string> parse_triple(std::string_view text, std::array<double, 3>& value,
                                        std::array<std::string, 3>* tokens = nullptr);
std::optional<std::string> parse_seed(std::string_view text, uint64_t& value);
std::optional<std::string> parse_region(std::string_view text, std::array<int64_t, 4>& value);
std::optional<std::string> parse_name(std::string_view text, std::span<const std::string_view> names, size_t& index,
                                      bool any_case = false);

// Parses text as row's type into v, with each component's token as typed
// (cut short) in tokens, for messages; the range is checked later.
std::optional<std::string> parse_value(const setting& row, std::string_view text, value& v,
                                       std::array<std::string, 3>& tokens);

// Why a value is outside row's range ("'0' is too small (at least 1)"), or
// nullopt; tokens: as the user gave the value (for a typed value, its text).
std::optional<std::string> check_range(const setting& row, const value& v, const std::array<std::string, 3>& tokens);

// Why the region r (x0, y0, x1, y1; token: as the user gave it) is not a
// window of a width x height image, or nullopt: its bounds depend on the
// image, so they are checked once the image is known.
std::optional<std::string> check_region(const std::array<int64_t, 4>& r, int64_t width, int64_t height,
                                        std::string_view token);

// The frames a frames value selects of a trajectory of `count` (Python's
// rules: an index from the end where negative, a slice clipped to the
// frames), in order, or why not: an index beyond the frames. A slice may
// select none.
std::optional<std::string> select_frames(const value& v, size_t count, std::vector<size_t>& out);

}  // namespace raycast
