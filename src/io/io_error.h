// The one kind of failure the writing code reports: a runtime error to print
// as "raycast: error: <what>" with exit status 1. The message names the file
// and the cause.
#pragma once
#include <stdexcept>

namespace raycast::io {

struct io_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace raycast::io
