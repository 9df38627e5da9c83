// SOURCE_DATE_EPOCH (reproducible-builds.org): the DateTime EXR and TIFF record instead of now.
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
