// What the text formats share (LAMMPS dumps, XYZ): a frame is a header that
// says how many rows follow, then those rows, one a line. The trajectory
// keeps where each frame begins (its byte offset in the text and its first
// line's number), found by one scan that reads each header and counts the
// rows' line breaks without parsing them; read(k) then parses frame k alone.
// Frames read in order extend the index as they go, so reading a file from
// its first frame to its last reads its bytes once, and frame_count() after
// them costs nothing more. A format provides the header's and the rows'
// parsers.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "formats/format.h"
#include "formats/input/line_cursor.h"
#include "formats/input/text_source.h"

namespace raycast::formats::input {

// "frame k (line L): what", thrown as a format_error.
[[noreturn]] void fail_at(size_t k, uint64_t line, const std::string& what);

class text_trajectory : public trajectory {
 public:
  explicit text_trajectory(std::unique_ptr<text_source> src) : src_(std::move(src)), cur_(*src_) {}
  size_t frame_count() override;
  bool has_frame(size_t k) override;
  particle_frame read(size_t k, const wanted_columns& wanted) override;

 protected:
  // Parses frame k's header (the cursor on its first line) and keeps what
  // read_rows needs; returns the number of rows that follow.
  virtual uint64_t read_header(line_cursor& c, size_t k) = 0;
  // Parses the rows of the header just read, exactly `rows` lines.
  virtual particle_frame read_rows(line_cursor& c, size_t k, uint64_t rows, const wanted_columns& wanted) = 0;

  // How many of `rows` rows (each at least min_row_bytes long, its line
  // break included) the rest of the text can hold, and one more: what a
  // reader allocates for a frame before reading it, so that a count that
  // lies is never allocated for. The rows a file really has never exceed it:
  // the loop meets the file's end or a malformed row first.
  uint64_t capacity(uint64_t rows, uint64_t min_row_bytes) const;

 private:
  struct mark {
    uint64_t offset, line;  // where frame k's text begins (blank lines before it included)
  };
  bool start(size_t k);  // the cursor at frame k's first line; false at the text's end
  void scan_one();       // finds where the next unindexed frame ends
  template <class Body>
  auto framed(size_t k, Body body);  // body(), its errors named by frame and line

  std::unique_ptr<text_source> src_;
  line_cursor cur_;
  std::vector<mark> marks_{{0, 0}};  // marks_[k] for each frame indexed, and the one after the last
  bool complete_ = false;            // marks_.back() is the text's end
};

}  // namespace raycast::formats::input
