#include "io/timestamp.h"

#include <charconv>
#include <cstdlib>
#include <cstring>

namespace raycast::io {

source_date source_date_epoch() {
  const char* v = std::getenv("SOURCE_DATE_EPOCH");
  if (!v || !*v) return {};
  int64_t s = 0;
  const char* end = v + std::strlen(v);
  const auto [p, ec] = std::from_chars(v, end, s);
  // Whole seconds, up to the year 9999 (what "YYYY:MM:DD" can say).
  if (ec != std::errc() || p != end || s < 0 || s > 253402300799) {
    std::string why(1, '\'');  // appended: "'" + ... draws a spurious -Wrestrict
    why += v;
    why += "' is not a number of seconds since 1970-01-01 UTC (0 to 253402300799)";
    return {std::nullopt, why};
  }
  return {s, std::nullopt};
}

}  // namespace raycast::io
