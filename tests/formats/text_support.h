// What the text formats' tests share: a file's text in memory, plain or
// gzipped by zlib, read by a reader of ours; the refusal a read ends in; the
// process's peak memory.
#pragma once
#include <gtest/gtest.h>
#include <zlib.h>

#include <fstream>
#include <functional>
#include <memory>
#include <string>

#include "formats/input/text_source.h"

namespace raycast_test {

// text gzipped (one member, zlib's default level), streamed from a producer
// that appends to its argument until it returns false, so that a bomb's
// gigabytes never sit in memory.
inline std::string gzip_stream(const std::function<bool(std::string&)>& produce) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out, in;
  char buf[1 << 16];
  bool more = true;
  while (more) {
    in.clear();
    more = produce(in);
    z.next_in = reinterpret_cast<Bytef*>(in.data());
    z.avail_in = uInt(in.size());
    do {
      z.next_out = reinterpret_cast<Bytef*>(buf);
      z.avail_out = sizeof buf;
      deflate(&z, more ? Z_NO_FLUSH : Z_FINISH);
      out.append(buf, sizeof buf - z.avail_out);
    } while (z.avail_out == 0);
  }
  deflateEnd(&z);
  return out;
}

inline std::string gzip(const std::string& text) {
  return gzip_stream([&](std::string& in) {
    in = text;
    return false;
  });
}

// The message of the format_error that f throws ("" if none).
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const raycast::formats::format_error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "not one line: " << e.what();
    return e.what();
  }
  return "";
}

// The process's peak resident memory (VmHWM), in bytes.
inline double peak_rss() {
  std::ifstream in("/proc/self/status");
  std::string key;
  double kb = 0;
  while (in >> key) {
    if (key == "VmHWM:" && in >> kb) return kb * 1024.0;
    in.ignore(1 << 20, '\n');
  }
  return 0;
}

// A source that counts the bytes read through it and the seeks behind its
// position (a gzip source's restarts), wrapped around another.
struct source_counts {
  uint64_t bytes = 0, rewinds = 0;
};
class counting_source final : public raycast::formats::input::text_source {
 public:
  counting_source(std::unique_ptr<text_source> s, source_counts& counts) : s_(std::move(s)), counts_(counts) {}
  size_t read(char* to, size_t n) override {
    const size_t k = s_->read(to, n);
    counts_.bytes += k;
    return k;
  }
  void seek(uint64_t offset) override {
    if (offset < s_->position()) ++counts_.rewinds;
    s_->seek(offset);
  }
  uint64_t position() const override { return s_->position(); }
  uint64_t max_text_bytes() const override { return s_->max_text_bytes(); }
  bool gzipped() const override { return s_->gzipped(); }

 private:
  std::unique_ptr<text_source> s_;
  source_counts& counts_;
};

}  // namespace raycast_test
