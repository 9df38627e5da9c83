// The text of a particle file, read forward: a plain file through pread, or
// a gzip file (recognized by its magic bytes, whatever its name) inflated
// by zlib as it is read. Either way the caller sees the same bytes, the
// decompressed text, at offsets into it; memory is the caller's window, never
// the whole file.
//
// A gzip file is inflated a few blocks ahead by a thread of the source's
// own (1 MiB at most), so that inflating and parsing overlap where a second
// core is free.
//
// zlib, not libdeflate: libdeflate decompresses a whole member into a buffer
// of its final size, which a gzip file does not say (ISIZE is the size modulo
// 2^32 and may lie), so a frame of a large .gz could only be read after the
// whole file was inflated into memory. zlib's inflate streams into a buffer
// of our size, so a trajectory's memory stays one frame's, and a gzip bomb
// inflates only as far as a frame can need.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace raycast::formats::input {

class text_source {
 public:
  virtual ~text_source() = default;
  // The next bytes of the text from the current position into to, up to n;
  // 0 only at the text's end. Throws format_error (io set) when the file
  // cannot be read; format_error naming the byte offset into the file when
  // a gzip stream is corrupt.
  virtual size_t read(char* to, size_t n) = 0;
  // Moves to offset of the text. A plain file moves at once; a gzip file
  // inflates forward from where it is, or from its start when offset lies
  // behind (gzip has no index: reading frames in order never goes back).
  virtual void seek(uint64_t offset) = 0;
  virtual uint64_t position() const = 0;
  // The most text the file can give: its size, or for a gzip file its size
  // times deflate's largest ratio (1032:1). A count that promises more rows
  // than this can hold is refused before anything is allocated for it.
  virtual uint64_t max_text_bytes() const = 0;
  virtual bool gzipped() const = 0;
};

// Opens path (regular files only, never blocking on a FIFO or device).
// Throws format_error with io set: strerror's words, "is a directory, ...".
std::unique_ptr<text_source> open_text(const std::string& path);

// The bytes of a buffer as a source (the tests' and fuzzers'): plain text,
// or gzip if they begin with its magic. They must outlive the source.
std::unique_ptr<text_source> memory_text(const char* data, size_t size);

// Deflate's largest ratio of output to input bytes.
inline constexpr uint64_t max_deflate_ratio = 1032;

}  // namespace raycast::formats::input
