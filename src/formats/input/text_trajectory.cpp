#include "formats/input/text_trajectory.h"

#include <algorithm>

#include "formats/input/fields.h"

namespace raycast::formats::input {

void fail_at(size_t k, uint64_t line, const std::string& what) {
  throw format_error("frame " + std::to_string(k) + " (line " + std::to_string(line) + "): " + what);
}

uint64_t text_trajectory::capacity(uint64_t rows, uint64_t min_row_bytes) const {
  const uint64_t have = src_->max_text_bytes(), at = cur_.offset();
  const uint64_t most = at < have ? (have - at + 1) / min_row_bytes : 0;  // the last row may lack its line break
  // One more: a row past them is malformed (shorter than any whole row), and
  // parsing it names what is wrong with it.
  return std::min(rows, most + 1);
}

// Errors from below (a corrupt gzip stream, an endless line) are named by
// the frame and the line being read.
template <class Body>
auto text_trajectory::framed(size_t k, Body body) {
  try {
    return body();
  } catch (const format_error& e) {
    if (std::string_view(e.what()).starts_with("frame ")) throw;
    throw format_error("frame " + std::to_string(k) + " (line " + std::to_string(cur_.line() + 1) + "): " + e.what(),
                       e.io);
  }
}

bool text_trajectory::start(size_t k) {
  cur_.seek(marks_[k].offset, marks_[k].line);
  std::string_view line;
  while (cur_.peek(line)) {
    if (!fields(line).done()) return true;
    cur_.next(line);
  }
  return false;
}

void text_trajectory::scan_one() {
  const size_t k = marks_.size() - 1;
  framed(k, [&] {
    if (!start(k)) {
      complete_ = true;
      return;
    }
    const uint64_t rows = read_header(cur_, k);
    const uint64_t first = cur_.line() + 1, got = cur_.skip(rows);
    if (got < rows)
      fail_at(k, first + got, "the header promises " + std::to_string(rows) + " atoms; the file ends after " +
                               std::to_string(got));
    marks_.push_back({cur_.offset(), cur_.line()});
  });
}

size_t text_trajectory::frame_count() {
  while (!complete_) scan_one();
  return marks_.size() - 1;
}

bool text_trajectory::has_frame(size_t k) {
  while (!complete_ && marks_.size() - 1 <= k) scan_one();
  return k < marks_.size() - 1;
}

particle_frame text_trajectory::read(size_t k, const wanted_columns& wanted) {
  while (!complete_ && marks_.size() - 1 < k) scan_one();
  return framed(k, [&] {
    if (k >= marks_.size() - (complete_ ? 1 : 0) || !start(k))
      throw format_error("frame " + std::to_string(k) + ": the file has " + std::to_string(frame_count()) +
                         " frames");
    const uint64_t rows = read_header(cur_, k);
    particle_frame f = read_rows(cur_, k, rows, wanted);
    if (k == marks_.size() - 1) marks_.push_back({cur_.offset(), cur_.line()});
    return f;
  });
}

}  // namespace raycast::formats::input
