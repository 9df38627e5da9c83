// Lines of a text source, read forward through a window of its bytes: the
// window holds the lines not yet consumed, at most max_line_bytes for one
// line, so a file without line breaks (or a gzip bomb of one endless line)
// costs that much memory and no more.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

#include "formats/input/text_source.h"

namespace raycast::formats::input {

// The longest line read; a longer one is refused ("a line longer than ...").
inline constexpr size_t max_line_bytes = size_t(1) << 22;
// Bytes readable after every line the cursor returns (its window's spare
// end): fields.h's parse_number_padded reads eight bytes at a time.
inline constexpr size_t line_padding = 16;

class line_cursor {
 public:
  explicit line_cursor(text_source& src) : src_(&src) {}

  // Moves to offset (the start of a line whose number is line).
  void seek(uint64_t offset, uint64_t line);

  // The next line, without its "\n" (nor a "\r" before it); false at the
  // end of the text. The view is valid until the next call.
  bool next(std::string_view& line) {
    if (!has_line()) return false;
    line = std::string_view(buf_.data() + begin_, size_t(eol_ - begin_));
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    begin_ = eol_ + (eol_ < end_ ? 1 : 0);
    eol_ = npos;
    ++line_;
    return true;
  }
  // The next line, not consumed (next() returns it again).
  bool peek(std::string_view& line) {
    if (!has_line()) return false;
    line = std::string_view(buf_.data() + begin_, size_t(eol_ - begin_));
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return true;
  }
  // Skips n lines, returning how many there were (fewer at the end).
  uint64_t skip(uint64_t n);

  uint64_t offset() const { return base_ + begin_; }  // the next line's first byte, in the text
  uint64_t line() const { return line_; }             // the number of the line last returned (1-based)
  text_source& source() const { return *src_; }

 private:
  static constexpr size_t npos = ~size_t(0);
  // Finds the end of the next line (eol_), reading more as needed.
  bool has_line() {
    if (eol_ != npos) return true;
    const void* nl = begin_ < end_ ? std::memchr(buf_.data() + begin_, '\n', end_ - begin_) : nullptr;
    if (!nl) return more();
    eol_ = size_t(static_cast<const char*>(nl) - buf_.data());
    return true;
  }
  bool more();
  bool fill();

  text_source* src_;
  std::vector<char> buf_;
  size_t begin_ = 0, end_ = 0;  // the unconsumed bytes, buf_[begin_, end_)
  size_t eol_ = npos;           // the next line's '\n' (or end_ for the last line), once found
  uint64_t base_ = 0;           // the text offset of buf_[0]
  uint64_t line_ = 0;
  bool eof_ = false;
};

}  // namespace raycast::formats::input
