#include "formats/gsd/hoomd.h"

#include <bit>
#include <cmath>
#include <cstring>

#include "formats/gsd/gsd_file.h"
#include "formats/input/fields.h"
#include "formats/input/mapped_file.h"

namespace raycast::formats {
namespace {

using gsd::chunk;

constexpr bool big_endian = std::endian::native == std::endian::big;
const float zeros[3] = {0, 0, 0};
const float half = 0.5f;
const uint32_t type_zero = 0;

[[noreturn]] void fail(size_t k, uint64_t byte, const std::string& what) {
  throw format_error("frame " + std::to_string(k) + " (byte " + std::to_string(byte) + "): " + what);
}

// What a frame's columns keep alive: the file's bytes, and what had to be
// decoded (radii from diameters, properties of types a column cannot view).
struct frame_memory {
  std::shared_ptr<const void> file;
  std::unique_ptr<float[]> radii;
  std::vector<std::unique_ptr<double[]>> decoded;
};

class hoomd_trajectory final : public trajectory {
 public:
  hoomd_trajectory(std::shared_ptr<const gsd::gsd_file> file, std::shared_ptr<const input::mapped_file> map)
      : file_(std::move(file)), map_(std::move(map)) {}
  size_t frame_count() override { return file_->frames(); }
  particle_frame read(size_t k, const wanted_columns& wanted) override;

 private:
  std::optional<chunk> either(size_t k, std::string_view name) const {
    if (auto c = file_->find(k, name)) return c;
    return k == 0 ? std::nullopt : file_->find(0, name);
  }
  uint64_t count(size_t k, size_t frame) const;
  std::optional<chunk> per_particle(size_t k, std::string_view name, uint64_t n, int components) const;
  api::column view(const chunk& c, frame_memory& m) const;
  void positions(size_t k, particle_frame& f) const;
  void types(size_t k, particle_frame& f) const;
  void radii(size_t k, particle_frame& f, frame_memory& m) const;
  void cell(size_t k, particle_frame& f) const;
  void properties(size_t k, particle_frame& f, frame_memory& m, const wanted_columns& wanted) const;

  std::shared_ptr<const gsd::gsd_file> file_;
  std::shared_ptr<const input::mapped_file> map_;  // null for bytes in memory
  uint64_t n0_ = 0;                                // frame 0's count
};

// particles/N of a frame (frame 0's where it has none; 0 where neither has).
uint64_t hoomd_trajectory::count(size_t k, size_t frame) const {
  const std::optional<chunk> c = frame == 0 ? file_->find(0, "particles/N") : either(frame, "particles/N");
  if (!c) return 0;
  if (c->type != gsd::u32 || c->N * c->M != 1) fail(k, c->entry, "particles/N is not one uint32");
  return gsd::load_le<uint32_t>(file_->at(c->location));
}

// A per-particle chunk: this frame's, else frame 0's while the count is
// frame 0's; its rows must be the count and its columns `components`.
std::optional<chunk> hoomd_trajectory::per_particle(size_t k, std::string_view name, uint64_t n,
                                                    int components) const {
  std::optional<chunk> c = file_->find(k, name);
  if (!c && k != 0 && n == n0_) c = file_->find(0, name);
  if (!c) return c;
  if (c->N != n)
    fail(k, c->entry, input::printable(name) + " has " + std::to_string(c->N) + " rows; particles/N is " + std::to_string(n));
  if (components > 0 && c->M != uint32_t(components))
    fail(k, c->entry, input::printable(name) + " has " + std::to_string(c->M) + " columns, not " + std::to_string(components));
  if (map_) map_->will_need(c->location, c->bytes());
  return c;
}

// A chunk as a column: in place where a column can read its type, else
// decoded into doubles.
api::column hoomd_trajectory::view(const chunk& c, frame_memory& m) const {
  const unsigned char* p = file_->at(c.location);
  const auto each = std::ptrdiff_t(gsd::type_size(c.type));
  const auto in_place = [&](api::element e) { return api::column{p, e, each * c.M, each, big_endian}; };
  switch (c.type) {
    case gsd::f32: return in_place(api::element::f32);
    case gsd::f64: return in_place(api::element::f64);
    case gsd::u32: return in_place(api::element::u32);
    case gsd::i32: return in_place(api::element::i32);
    default: break;
  }
  const size_t n = size_t(c.N * c.M);
  auto out = std::make_unique_for_overwrite<double[]>(n);
  for (size_t j = 0; j < n; ++j) {
    const unsigned char* q = p + j * size_t(each);
    switch (c.type) {
      case gsd::u8: out[j] = q[0]; break;
      case gsd::i8: out[j] = double(int8_t(q[0])); break;
      case gsd::u16: out[j] = gsd::load_le<uint16_t>(q); break;
      case gsd::i16: out[j] = double(int16_t(gsd::load_le<uint16_t>(q))); break;
      case gsd::u64: out[j] = double(gsd::load_le<uint64_t>(q)); break;
      default: out[j] = double(int64_t(gsd::load_le<uint64_t>(q))); break;
    }
  }
  const api::column col{out.get(), api::element::f64, std::ptrdiff_t(sizeof(double)) * c.M, sizeof(double)};
  m.decoded.push_back(std::move(out));
  return col;
}

void hoomd_trajectory::positions(size_t k, particle_frame& f) const {
  const std::optional<chunk> c = per_particle(k, "particles/position", f.count, 3);
  if (!c) {
    if (f.count > 0)
      fail(k, either(k, "particles/N")->location,
           "particles/N is " + std::to_string(f.count) + " but there is no particles/position (in this frame or frame 0)");
    f.positions = {zeros, api::element::f32, 0, 4};
    return;
  }
  if (c->type != gsd::f32 && c->type != gsd::f64) fail(k, c->entry, "particles/position is not float32 or float64");
  const size_t each = gsd::type_size(c->type);
  const unsigned char* p = file_->at(c->location);
  for (size_t j = 0; j < size_t(c->N) * 3; ++j) {
    const double v = each == 4 ? double(std::bit_cast<float>(gsd::load_le<uint32_t>(p + 4 * j)))
                               : std::bit_cast<double>(gsd::load_le<uint64_t>(p + 8 * j));
    if (!std::isfinite(v))
      fail(k, c->location + j * each, "particles/position of particle " + std::to_string(j / 3) + " is not finite");
  }
  frame_memory unused;
  f.positions = view(*c, unused);
}

void hoomd_trajectory::types(size_t k, particle_frame& f) const {
  if (const std::optional<chunk> t = either(k, "particles/types")) {
    if (t->type != gsd::i8 && t->type != gsd::u8 && t->type != gsd::character)
      fail(k, t->entry, "particles/types is not strings (int8 rows)");
    const char* p = reinterpret_cast<const char*>(file_->at(t->location));
    for (uint64_t j = 0; j < t->N; ++j) f.type_names.emplace_back(p + j * t->M, strnlen(p + j * t->M, t->M));
  } else {
    f.type_names = {"A"};
  }
  const std::optional<chunk> c = per_particle(k, "particles/typeid", f.count, 1);
  if (!c) {
    f.types = api::column{&type_zero, api::element::u32, 0, 4};
    return;
  }
  if (c->type != gsd::u32) fail(k, c->entry, "particles/typeid is not uint32");
  const unsigned char* p = file_->at(c->location);
  for (size_t j = 0; j < f.count; ++j)
    if (gsd::load_le<uint32_t>(p + 4 * j) >= f.type_names.size())
      fail(k, c->location + 4 * j, "particles/typeid of particle " + std::to_string(j) + " is " +
                                       std::to_string(gsd::load_le<uint32_t>(p + 4 * j)) + "; there are " +
                                       std::to_string(f.type_names.size()) + " types");
  frame_memory unused;
  f.types = view(*c, unused);
}

void hoomd_trajectory::radii(size_t k, particle_frame& f, frame_memory& m) const {
  const std::optional<chunk> c = per_particle(k, "particles/diameter", f.count, 1);
  if (!c) {
    f.radii = api::column{&half, api::element::f32, 0, 4};
    return;
  }
  if (c->type != gsd::f32) fail(k, c->entry, "particles/diameter is not float32");
  m.radii = std::make_unique_for_overwrite<float[]>(size_t(f.count));
  const unsigned char* p = file_->at(c->location);
  for (size_t j = 0; j < f.count; ++j) {
    const float d = std::bit_cast<float>(gsd::load_le<uint32_t>(p + 4 * j));
    if (!std::isfinite(d) || d < 0)
      fail(k, c->location + 4 * j, "particles/diameter of particle " + std::to_string(j) + " is not a finite size");
    m.radii[j] = d * 0.5f;
  }
  f.radii = api::packed(m.radii.get());
}

// configuration/box: Lx Ly Lz xy xz yz, the box centred on the origin with
// edges a = (Lx, 0, 0), b = (xy Ly, Ly, 0), c = (xz Lz, yz Lz, Lz).
void hoomd_trajectory::cell(size_t k, particle_frame& f) const {
  double b[6] = {1, 1, 1, 0, 0, 0};
  if (const std::optional<chunk> c = either(k, "configuration/box")) {
    if (c->type != gsd::f32 || c->N * c->M != 6) fail(k, c->entry, "configuration/box is not six float32");
    for (int j = 0; j < 6; ++j) b[j] = std::bit_cast<float>(gsd::load_le<uint32_t>(file_->at(c->location + 4 * j)));
    for (int j = 0; j < 6; ++j)
      if (!std::isfinite(b[j]) || (j < 3 && b[j] < 0)) fail(k, c->location + 4 * j, "configuration/box is not a box");
  }
  uint8_t dimensions = 3;
  if (const std::optional<chunk> d = either(k, "configuration/dimensions"); d && d->type == gsd::u8)
    dimensions = *file_->at(d->location);
  particle_cell cell;
  cell.a = {b[0], 0, 0};
  cell.b = {b[3] * b[1], b[1], 0};
  cell.c = {b[4] * b[2], b[5] * b[2], b[2]};
  cell.origin = {-(cell.a.x + cell.b.x + cell.c.x) / 2, -(cell.b.y + cell.c.y) / 2, -cell.c.z / 2};
  cell.periodic = {true, true, dimensions == 3};
  f.cell = cell;
  f.timestep = 0;  // the schema's default
  if (const std::optional<chunk> s = either(k, "configuration/step"); s && s->type == gsd::u64)
    f.timestep = int64_t(gsd::load_le<uint64_t>(file_->at(s->location)));
}

void hoomd_trajectory::properties(size_t k, particle_frame& f, frame_memory& m, const wanted_columns& wanted) const {
  for (std::string_view name : file_->names("particles/")) {
    const std::string_view p = name.substr(10);
    if (p == "N" || p == "position" || p == "typeid" || p == "types" || p == "diameter" || p == "type_shapes")
      continue;
    if (!wanted.wants(p)) continue;
    if (const std::optional<chunk> c = per_particle(k, name, f.count, 0))
      f.properties.push_back({std::string(p), view(*c, m), int(c->M)});
  }
}

particle_frame hoomd_trajectory::read(size_t k, const wanted_columns& wanted) {
  if (k >= file_->frames())
    throw format_error("frame " + std::to_string(k) + ": the file has " + std::to_string(file_->frames()) + " frames");
  n0_ = count(k, 0);
  particle_frame f;
  f.count = size_t(count(k, k));
  auto m = std::make_shared<frame_memory>();
  m->file = file_;
  positions(k, f);
  types(k, f);
  radii(k, f, *m);
  cell(k, f);
  properties(k, f, *m, wanted);
  f.owner = std::move(m);
  return f;
}

std::shared_ptr<const gsd::gsd_file> hoomd_file(const unsigned char* data, uint64_t size,
                                                std::shared_ptr<const void> owner) {
  auto file = std::make_shared<const gsd::gsd_file>(data, size, std::move(owner));
  if (file->schema() != "hoomd")
    throw format_error("header (byte 112): the schema is " + input::quoted(file->schema()) + ", not hoomd");
  return file;
}

std::unique_ptr<trajectory> open_mapped(const std::string& path) {
  auto map = input::mapped_file::open(path);
  auto file = hoomd_file(map->data(), map->size(), map);
  return std::make_unique<hoomd_trajectory>(std::move(file), std::move(map));
}

bool sniff_gsd(std::string_view head) { return gsd::has_gsd_magic(head); }

constexpr std::string_view gsd_extensions[] = {".gsd"};

}  // namespace

std::unique_ptr<trajectory> open_gsd(const unsigned char* data, uint64_t size, std::shared_ptr<const void> owner) {
  return std::make_unique<hoomd_trajectory>(hoomd_file(data, size, std::move(owner)), nullptr);
}

const format& gsd_format() {
  static const format f{"gsd", gsd_extensions, sniff_gsd, open_mapped};
  return f;
}

}  // namespace raycast::formats
