// Movies (-o melt.mp4, .webm, .gif): rendered frames piped to Debian's
// ffmpeg as raw RGB, no temporary images; the movie goes to a file with no
// name beside the destination (io/files/atomic_file.h), renamed into place
// only once ffmpeg has finished it, so a failed or interrupted run leaves
// what was there. ffmpeg's messages are kept, not printed: a failure is one
// line quoting its last.
#pragma once
#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace raycast::io {

class atomic_file;

enum class movie_kind : uint8_t { mp4, webm, gif };

// The movie a file name's extension asks for (.mp4, .webm, .gif, any case), or none.
std::optional<movie_kind> movie_kind_of(const std::string& path);

// Why a movie cannot be written here (no ffmpeg on PATH: which package to
// install), or nullopt.
std::optional<std::string> movie_unavailable();

class movie_writer {
 public:
  // Starts ffmpeg writing a width x height movie at fps frames a second.
  // Throws io_error naming path.
  movie_writer(const std::string& path, movie_kind kind, int64_t width, int64_t height, int fps);
  ~movie_writer();  // stops ffmpeg and removes the temporary unless finished
  movie_writer(const movie_writer&) = delete;
  movie_writer& operator=(const movie_writer&) = delete;

  // One frame: height rows of width RGB8 pixels, row r at rgb + r * stride.
  void add_frame(const unsigned char* rgb, size_t stride);
  // Ends the movie: ffmpeg finishes it and it is renamed into place.
  void finish();

 private:
  [[noreturn]] void fail(const std::string& why);
  std::string path_;
  int64_t width_, height_;
  std::unique_ptr<atomic_file> file_;
  int stdin_ = -1, messages_ = -1;
  pid_t pid_ = -1;
};

}  // namespace raycast::io
