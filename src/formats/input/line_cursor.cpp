#include "formats/input/line_cursor.h"

#include <algorithm>
#include <string>

#include "formats/format.h"

namespace raycast::formats::input {
namespace {
constexpr size_t block_bytes = size_t(1) << 18;  // what one read asks for: a few L2's worth
}

void line_cursor::seek(uint64_t offset, uint64_t line) {
  eol_ = npos;
  line_ = line;
  if (offset >= base_ && offset <= base_ + end_) {
    begin_ = size_t(offset - base_);
    return;
  }
  src_->seek(offset);
  base_ = offset;
  begin_ = end_ = 0;
  eof_ = src_->position() != offset;  // a gzip text shorter than offset
}

bool line_cursor::fill() {
  if (buf_.size() < block_bytes) buf_.resize(block_bytes);
  if (begin_ > 0) {  // keep only what is unconsumed
    std::memmove(buf_.data(), buf_.data() + begin_, end_ - begin_);
    base_ += begin_;
    end_ -= begin_;
    begin_ = 0;
  }
  if (end_ + line_padding == buf_.size()) {
    if (buf_.size() > max_line_bytes)
      throw format_error("a line longer than " + std::to_string(max_line_bytes) + " bytes");
    buf_.resize(buf_.size() * 2);
  }
  const size_t got = src_->read(buf_.data() + end_, buf_.size() - line_padding - end_);
  end_ += got;
  if (got == 0) eof_ = true;
  return got > 0;
}

bool line_cursor::more() {
  for (;;) {
    const size_t searched = end_ - begin_;  // bytes known to hold no '\n'
    if (eof_ || !fill()) {
      if (begin_ == end_) return false;
      eol_ = end_;  // the last line, without a line break
      return true;
    }
    const void* nl = std::memchr(buf_.data() + begin_ + searched, '\n', end_ - begin_ - searched);
    if (nl) {
      eol_ = size_t(static_cast<const char*>(nl) - buf_.data());
      return true;
    }
  }
}

uint64_t line_cursor::skip(uint64_t n) {
  uint64_t done = 0;
  eol_ = npos;
  while (done < n) {
    const char* p = buf_.data() + begin_;
    const char* const e = buf_.data() + end_;
    while (done < n && p < e) {
      const void* nl = std::memchr(p, '\n', size_t(e - p));
      if (!nl) break;
      p = static_cast<const char*>(nl) + 1;
      ++done;
    }
    begin_ = size_t(p - buf_.data());
    if (done == n || !has_line()) break;
    begin_ = eol_ + (eol_ < end_ ? 1 : 0);  // the line that ran past the window
    eol_ = npos;
    ++done;
  }
  line_ += done;
  return done;
}

}  // namespace raycast::formats::input
