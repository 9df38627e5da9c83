#include "formats/input/text_source.h"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <variant>
#include <vector>

#include "formats/format.h"
#include "formats/regular_file.h"

namespace raycast::formats::input {
namespace {

// Where a source's raw bytes come from: a regular file or a caller's buffer.
class raw_bytes {
 public:
  virtual ~raw_bytes() = default;
  virtual uint64_t size() const = 0;
  // Up to n bytes at offset (fewer only at the end). Throws format_error (io).
  virtual size_t read_at(uint64_t offset, size_t n, char* to) const = 0;
};

class file_bytes final : public raw_bytes {
 public:
  explicit file_bytes(std::unique_ptr<regular_file> f) : f_(std::move(f)) {}
  uint64_t size() const override { return f_->size(); }
  size_t read_at(uint64_t offset, size_t n, char* to) const override {
    const ptrdiff_t got = f_->read_at(offset, n, to);
    if (got < 0) throw format_error(std::strerror(errno), true);
    return size_t(got);
  }

 private:
  std::unique_ptr<regular_file> f_;
};

class buffer_bytes final : public raw_bytes {
 public:
  buffer_bytes(const char* data, size_t size) : data_(data), size_(size) {}
  uint64_t size() const override { return size_; }
  size_t read_at(uint64_t offset, size_t n, char* to) const override {
    if (offset >= size_) return 0;
    const size_t k = std::min<uint64_t>(n, size_ - offset);
    std::memcpy(to, data_ + offset, k);
    return k;
  }

 private:
  const char* data_;
  size_t size_;
};

class plain_source final : public text_source {
 public:
  explicit plain_source(std::unique_ptr<raw_bytes> raw) : raw_(std::move(raw)) {}
  size_t read(char* to, size_t n) override {
    const size_t k = raw_->read_at(pos_, n, to);
    pos_ += k;
    return k;
  }
  void seek(uint64_t offset) override { pos_ = offset; }
  uint64_t position() const override { return pos_; }
  uint64_t max_text_bytes() const override { return raw_->size(); }
  bool gzipped() const override { return false; }

 private:
  std::unique_ptr<raw_bytes> raw_;
  uint64_t pos_ = 0;
};

// A gzip file (one member or several concatenated, as gzip and cat make
// them) inflated forward; a seek behind the current position starts again.
class gzip_source final : public text_source {
 public:
  explicit gzip_source(std::unique_ptr<raw_bytes> raw) : raw_(std::move(raw)), in_(size_t(1) << 18) {
    if (inflateInit2(&z_, 15 + 16) != Z_OK) throw format_error("zlib cannot start inflating", true);
  }
  ~gzip_source() override { inflateEnd(&z_); }

  size_t read(char* to, size_t n) override;
  void seek(uint64_t offset) override;
  uint64_t position() const override { return pos_; }
  uint64_t max_text_bytes() const override { return raw_->size() * max_deflate_ratio; }
  bool gzipped() const override { return true; }

 private:
  bool refill();
  uint64_t consumed() const { return in_at_ - z_.avail_in; }  // the compressed bytes inflate has taken
  [[noreturn]] void corrupt(const char* what) const {
    throw format_error("the gzip stream is " + std::string(what) + " at byte " + std::to_string(consumed()) +
                       " of the file");
  }

  std::unique_ptr<raw_bytes> raw_;
  std::vector<char> in_;
  z_stream z_{};
  uint64_t in_at_ = 0;  // the file's bytes read into in_ so far
  uint64_t pos_ = 0;    // the text's bytes given so far
  bool ended_ = false;  // the last member ended with the file
};

bool gzip_source::refill() {
  if (in_at_ >= raw_->size()) return false;
  const size_t k = raw_->read_at(in_at_, in_.size(), in_.data());
  if (k == 0) return false;
  in_at_ += k;
  z_.next_in = reinterpret_cast<Bytef*>(in_.data());
  z_.avail_in = uInt(k);
  return true;
}

size_t gzip_source::read(char* to, size_t n) {
  if (ended_ || n == 0) return 0;
  z_.next_out = reinterpret_cast<Bytef*>(to);
  z_.avail_out = uInt(std::min<size_t>(n, size_t(1) << 30));
  const uInt asked = z_.avail_out;
  while (z_.avail_out == asked) {
    if (z_.avail_in == 0 && !refill()) {
      if (consumed() == 0) return 0;  // an empty file: no text
      corrupt("cut short");
    }
    const int r = inflate(&z_, Z_NO_FLUSH);
    if (r == Z_STREAM_END) {
      // Another member may follow (concatenated gzip files); anything else is not gzip.
      if (z_.avail_in == 0 && !refill()) {
        ended_ = true;
        break;
      }
      if (z_.avail_in < 2 || z_.next_in[0] != 0x1f || z_.next_in[1] != 0x8b) corrupt("followed by bytes that are not gzip");
      inflateReset(&z_);
    } else if (r == Z_DATA_ERROR) {
      corrupt(z_.msg ? ("corrupt (" + std::string(z_.msg) + ")").c_str() : "corrupt");
    } else if (r == Z_MEM_ERROR) {
      throw format_error("zlib ran out of memory", true);
    } else if (r != Z_OK && r != Z_BUF_ERROR) {
      corrupt("unreadable");
    }
  }
  const size_t got = asked - z_.avail_out;
  pos_ += got;
  return got;
}

void gzip_source::seek(uint64_t offset) {
  if (offset < pos_) {
    inflateReset(&z_);
    z_.avail_in = 0;
    in_at_ = 0;
    pos_ = 0;
    ended_ = false;
  }
  std::vector<char> scratch;
  while (pos_ < offset) {
    scratch.resize(size_t(std::min<uint64_t>(offset - pos_, size_t(1) << 18)));
    if (read(scratch.data(), scratch.size()) == 0) break;
  }
}

// Another source read ahead by a thread of its own, at most `depth` blocks
// ahead: a gzip file inflates on one core while its text is parsed on
// another, and its memory stays those few blocks. Where no thread can be
// started, the source is read where it is asked.
class read_ahead final : public text_source {
 public:
  explicit read_ahead(std::unique_ptr<text_source> inner) : inner_(std::move(inner)) {}
  ~read_ahead() override { stop(); }
  size_t read(char* to, size_t n) override;
  void seek(uint64_t offset) override;
  uint64_t position() const override { return pos_; }
  uint64_t max_text_bytes() const override { return inner_->max_text_bytes(); }
  bool gzipped() const override { return inner_->gzipped(); }

 private:
  static constexpr size_t block_bytes = size_t(1) << 18, depth = 4;
  bool next_block();
  void work();
  void stop();

  std::unique_ptr<text_source> inner_;  // the worker's alone while it runs
  std::thread worker_;
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<std::vector<char>> ready_;  // blocks read, in order
  std::vector<std::vector<char>> spare_;
  bool stopping_ = false, finished_ = false, inline_ = false;
  std::exception_ptr error_;
  std::vector<char> block_;  // the block being given out, from at_
  size_t at_ = 0;
  uint64_t pos_ = 0;
};

void read_ahead::work() {
  for (;;) {
    std::vector<char> b;
    {
      std::unique_lock lock(m_);
      cv_.wait(lock, [&] { return stopping_ || ready_.size() < depth; });
      if (stopping_) return;
      if (!spare_.empty()) b = std::move(spare_.back()), spare_.pop_back();
    }
    size_t n = 0;
    std::exception_ptr error;
    try {
      b.resize(block_bytes);
      n = inner_->read(b.data(), b.size());
      b.resize(n);
    } catch (...) {
      error = std::current_exception();
    }
    std::lock_guard lock(m_);
    if (error || n == 0) {
      error_ = error;
      finished_ = true;
      cv_.notify_all();
      return;
    }
    ready_.push_back(std::move(b));
    cv_.notify_all();
  }
}

bool read_ahead::next_block() {
  if (inline_) {
    block_.resize(block_bytes);
    block_.resize(inner_->read(block_.data(), block_.size()));
    at_ = 0;
    return !block_.empty();
  }
  std::unique_lock lock(m_);
  if (!worker_.joinable() && !finished_) {
    try {
      worker_ = std::thread([this] { work(); });
    } catch (const std::system_error&) {
      inline_ = true;
      lock.unlock();
      return next_block();
    }
  }
  if (!block_.empty()) spare_.push_back(std::move(block_));
  block_.clear();
  at_ = 0;
  cv_.wait(lock, [&] { return !ready_.empty() || finished_; });
  if (ready_.empty()) {
    if (error_) std::rethrow_exception(error_);
    return false;
  }
  block_ = std::move(ready_.front());
  ready_.pop_front();
  cv_.notify_all();
  return true;
}

size_t read_ahead::read(char* to, size_t n) {
  if (at_ == block_.size() && !next_block()) return 0;
  const size_t k = std::min(n, block_.size() - at_);
  std::memcpy(to, block_.data() + at_, k);
  at_ += k;
  pos_ += k;
  return k;
}

void read_ahead::stop() {
  {
    std::lock_guard lock(m_);
    stopping_ = true;
  }
  cv_.notify_all();
  if (worker_.joinable()) worker_.join();
  stopping_ = false;
}

void read_ahead::seek(uint64_t offset) {
  if (offset < pos_) {  // behind: the inner source starts again
    stop();
    inner_->seek(offset);
    ready_.clear();
    block_.clear();
    at_ = 0;
    pos_ = inner_->position();
    finished_ = false;
    error_ = nullptr;
  }
  char scratch[4096];
  while (pos_ < offset && read(scratch, size_t(std::min<uint64_t>(sizeof scratch, offset - pos_))) > 0) {
  }
}

bool is_gzip(const raw_bytes& raw) {
  unsigned char magic[2] = {0, 0};
  return raw.read_at(0, 2, reinterpret_cast<char*>(magic)) == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
}

std::unique_ptr<text_source> source_of(std::unique_ptr<raw_bytes> raw) {
  if (is_gzip(*raw)) return std::make_unique<read_ahead>(std::make_unique<gzip_source>(std::move(raw)));
  return std::make_unique<plain_source>(std::move(raw));
}

}  // namespace

std::unique_ptr<text_source> open_text(const std::string& path) {
  auto opened = regular_file::open(path);
  if (auto* why = std::get_if<std::string>(&opened)) throw format_error(*why, true);
  return source_of(std::make_unique<file_bytes>(std::move(std::get<std::unique_ptr<regular_file>>(opened))));
}

std::unique_ptr<text_source> memory_text(const char* data, size_t size) {
  return source_of(std::make_unique<buffer_bytes>(data, size));
}

}  // namespace raycast::formats::input
