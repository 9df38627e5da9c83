// A regular file mapped into memory read-only, for the binary formats whose
// arrays are read in place (GSD's chunks). Opened as regular_file opens
// (never blocking on a FIFO or device); the bytes stay mapped while a frame
// that views them is alive (its owner holds the mapping).
//
// A mapping shows a file as it is: a file cut short by another program while
// mapped makes reading past its new end fault (SIGBUS). The readers check
// every offset against the size the file had when opened, which is all a
// reader of a mapped file can do; a file being rewritten is not a file to
// render.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace raycast::formats::input {

class mapped_file {
 public:
  // Throws format_error (io set): strerror's words, "is a directory, ...".
  static std::shared_ptr<const mapped_file> open(const std::string& path);
  ~mapped_file();
  mapped_file(const mapped_file&) = delete;
  mapped_file& operator=(const mapped_file&) = delete;

  const unsigned char* data() const { return data_; }
  uint64_t size() const { return size_; }
  // Asks the kernel to read [offset, offset + n) ahead (a chunk about to be read).
  void will_need(uint64_t offset, uint64_t n) const;

 private:
  mapped_file(const unsigned char* data, uint64_t size) : data_(data), size_(size) {}
  const unsigned char* data_;
  uint64_t size_;
};

}  // namespace raycast::formats::input
