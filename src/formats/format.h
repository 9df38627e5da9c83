// A file format of the formats room: how the registry (formats/registry.h)
// recognizes it and how its frames are read. A reader is three verbs, as
// OVITO's file readers: detect (by content where the format defines a
// signature, else by name), scan (find where each frame begins, once), and
// read one frame (only its own bytes).
#pragma once
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "scene/particles.h"

namespace raycast::formats {

// Why a file cannot be read, in one line without the file's name (the
// caller puts it first): "frame 3 (line 12042): x is not a number". A frame
// error names the frame (its index in the file) and the line (text formats)
// or byte offset (binary ones). io: the file could not be read (an I/O
// failure, not bad content).
struct format_error : std::runtime_error {
  explicit format_error(const std::string& why, bool io_failure = false)
      : std::runtime_error(why), io(io_failure) {}
  bool io = false;
};

// The columns a render reads of a frame beyond positions, radii, colours and
// types: the properties named (--color-by's); `all` for every column (the
// Python module's frames()). A reader may skip the others' text unparsed.
struct wanted_columns {
  bool all = false;
  std::vector<std::string> properties;
  bool wants(std::string_view name) const {
    if (all) return true;
    for (const std::string& p : properties)
      if (p == name) return true;
    return false;
  }
};

// An open trajectory: its frames, each read on demand. Memory is about one
// frame's (plus the index of where frames begin), whatever the file's length.
class trajectory {
 public:
  virtual ~trajectory() = default;
  // The number of frames: the file scanned once (or the format's own index
  // read) for where each frame begins. Throws format_error.
  virtual size_t frame_count() = 0;
  // Whether frame k exists, the file scanned only as far as frame k (a text
  // trajectory); a frame before it that the scan cannot pass throws
  // format_error. A run over every frame reads them as they come, so that
  // the frames before a damaged one are rendered.
  virtual bool has_frame(size_t k) { return k < frame_count(); }
  // Frame k (k < frame_count()), reading only its own bytes. Throws
  // format_error naming the frame: cut short, a count that lies, missing
  // position columns, NaN or infinite coordinates, a value that is not a
  // number.
  virtual particle_frame read(size_t k, const wanted_columns& wanted) = 0;
};

struct format {
  std::string_view name;  // "lammps-dump", "extxyz", "gsd", "ply", "json"
  std::span<const std::string_view> extensions;  // ".lammpstrj", ...; lower case, with the dot
  // Whether a file's first bytes (up to 4 KiB, fewer for a short file;
  // decompressed for a .gz file) are this format's, where it has a signature
  // (PLY's "ply\n", GSD's magic, a dump's "ITEM: TIMESTEP", JSON's '{');
  // nullptr where only the name tells.
  bool (*sniff)(std::string_view head) = nullptr;
  // Opens a particle format's file (regular files only, never blocking on a
  // FIFO or device). Throws format_error.
  std::unique_ptr<trajectory> (*open)(const std::string& path) = nullptr;
};

}  // namespace raycast::formats
