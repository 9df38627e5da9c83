// The writing code's one failure: "raycast: error: <file>: <cause>", exit status 1.
#pragma once
#include <stdexcept>

namespace raycast::io {

struct io_error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace raycast::io
