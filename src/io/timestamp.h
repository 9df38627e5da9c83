// SOURCE_DATE_EPOCH (https://reproducible-builds.org/specs/source-date-epoch/):
// the time EXR and TIFF record as the image's DateTime instead of now, so two
// runs give the same bytes.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

namespace raycast::io {

struct source_date {
  std::optional<int64_t> seconds;    // since 1970-01-01 UTC; none when unset or empty
  std::optional<std::string> error;  // set when the value is not such a number
};

source_date source_date_epoch();

}  // namespace raycast::io
