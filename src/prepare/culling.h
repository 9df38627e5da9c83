// Culling: which spheres the rays of each row, and of each batch of a row,
// can hit. Compiled once (not per instruction set); the kernels only read
// what it builds.
//
// Two levels, so that a frame of N spheres costs O(N + entries), whatever
// the thread count or band size:
//  - per frame, a row index: for every image row, the spheres whose
//    bounding rows cover it (sphere_rows), in the float scene's order, each with the
//    columns it may touch. Built once by the renderer, in parallel over the
//    spheres, and read-only afterwards. In a depth-ordered scene, spheres
//    that nearer ones surely hide at every pixel of their box are left out
//    (occlusion, culling.cpp: a walk in depth order, on one thread). Memory:
//    8 bytes per row plus 8 bytes per entry (an entry is a sphere in a row it
//    may touch: its projected height in rows plus two), and while it is
//    built 20 bytes per sphere (with occlusion, per sphere kept, and a byte
//    a pixel).
//  - per row, while it is rendered: each listed sphere's batches (from its
//    columns, or for a tall sphere an exact quadratic in the column), turned
//    into one list per batch of columns (batch_culler). 12 bytes per listed
//    sphere, 4 bytes per batch entry and 16 per batch, per thread, reused
//    row after row.
// Every test is conservative: the margins are hundreds of times the float
// intersection's rounding, so leaving a sphere out never changes a pixel
// (tests/test_culling.cpp checks every hit against the lists).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "prepare/float_scene.h"
#include "memory/arrays.h"

namespace raycast {

// A sphere some ray of a row may hit, and the batches of `batch` columns
// (batch lo .. hi, inclusive: columns lo * batch .. hi * batch + batch - 1)
// whose rays may hit it.
struct sphere_span {
  uint32_t sphere;
  int32_t lo, hi;
};

// The spheres a ray of the row with this sv (kernels/scalar.h) may hit, in
// the float scene's order, with their batches. Every ray of a row lies in the plane
// through the camera origin spanned by centre + sv * vertical and horizontal,
// so a sphere whose centre is farther than its radius from that plane is hit
// by none of them; of the others, a column's ray can hit the sphere only if
// its line comes within the radius of the centre, a quadratic in the column.
// The tests are in double on the float renderers' own constants, with a
// margin (1e-5 of |f| + r) a hundred times the float intersection's
// rounding. Writes to out (room for every candidate) and returns how many.
// With candidates, only those spheres (in order) are considered: the
// others are known not to come near this row (sphere_rows).
// With spread (a float_scene's pixel_spread, for renders with many samples),
// the spheres a ray of the pixels' whole square of samples may hit: each
// radius widened by spread |f| (a ray within angle spread of another passes
// within spread |f| of where that one does, up to the sphere's distance).
size_t spheres_in_row(const float_scene& f, float sv, int batch, sphere_span* out,
                      const uint32_t* candidates = nullptr, size_t n_candidates = 0,
                      double spread = 0.0);

// The rows j (j = 0 at the bottom, kernels/scalar.h) whose plane may come
// near sphere k -- every row where spheres_in_row's plane test could keep
// it, and a little more; false when none does.
bool sphere_rows(const float_scene& f, uint32_t k, int64_t& j_lo, int64_t& j_hi, double spread = 0.0);

// A sphere in a row of the row index, with the columns its box may touch:
// lo << shift .. (hi << shift) + 2^shift - 1, the same in each of its rows,
// for a sphere at most a few dozen rows tall; lo = tall for a taller one,
// which is tested exactly in each row. shift (the index's) is 0 for images
// up to 65,535 columns wide; wider ones round boxes out to 2^shift columns.
struct row_entry {
  uint32_t sphere;
  uint16_t lo, hi;
  static constexpr uint16_t tall = 0xffff;
};

// Per frame: for each image row r (r = 0 at the top, as image_band), the
// spheres whose rows (sphere_rows) include it, in the float scene's order. A sphere every
// ray passes behind is in no row.
struct row_index {
  std::vector<uint64_t> first;  // list[first[r] .. first[r + 1]) for row r
  filled_array<row_entry> list;  // 8 bytes per entry
  size_t most = 0;                // the longest row's count
  size_t hidden = 0;              // spheres left out as hidden by nearer ones (occlusion)
  int shift = 0;                  // the entries' column unit, 2^shift

  // Built with up to `threads` threads; the same bytes for any count.
  static row_index build(const float_scene& f, double spread, int threads);
  size_t bytes() const { return first.size() * sizeof(uint64_t) + list.size() * sizeof(row_entry); }
};

// Per thread, per row: the lists of the spheres each batch of the row may
// hit (from the row index's candidates). Raw memory and out-of-line
// functions only: the kernels that use it are compiled per instruction set
// and must instantiate no standard-library template. Without memory (ok()
// false) a kernel tests every sphere, which is slow but right.
class batch_culler {
 public:
  // For rows of a frame whose rows have at most `most` candidates each, from
  // a row index whose column unit is 2^shift.
  batch_culler(const float_scene& f, size_t most, int shift, int batch, double spread);
  ~batch_culler();
  batch_culler(const batch_culler&) = delete;
  batch_culler& operator=(const batch_culler&) = delete;
  bool ok() const { return spans_ != nullptr; }

  // The row with this sv, from its entries in the row index: the batches of
  // each sphere its rays may hit; returns how many spheres it keeps.
  size_t row(float sv, const row_entry* entries, size_t count);
  // How many batches one run of lists may cover (runs keep the lists within
  // their memory however many batches the row's spheres span).
  int64_t run_length() const;
  // The lists of the row's batches [b0, b1) (b1 - b0 <= run_length()).
  void build(int64_t b0, int64_t b1);
  // Batch b's spheres (b in the last build's run; list(b) only where
  // tests(b) > 0).
  const uint32_t* list(int64_t b) const { return list_ + start_[b - b0_]; }
  size_t tests(int64_t b) const { return kept_ == 0 ? 0 : count_[b - b0_]; }

 private:
  void release();
  // The common case, in one pass over the row's entries: each batch's list
  // in its own slot of slot_ entries, appended to as the entries come; false
  // where a slot would overflow (what it wrote is then left for row() to
  // write over).
  bool row_in_slots(float sv, const row_entry* entries, size_t count);
  bool slotted_ = false;  // the row's lists are in slots: build has nothing to do
  // List entries one run may hold: the row's own entries where they fit in
  // four per candidate (each sphere in a few batches), else runs of fewer
  // batches (spheres that span much of the row).
  static constexpr size_t budget = size_t(1) << 16;
  size_t capacity_ = 0;
  size_t entries_ = 0;  // the kept spheres' batches, added up (rows not in slots)
  const float_scene& f_;
  int shift_;
  int batch_shift_;  // log2 of the batch's width (a vector's: a power of two)
  double spread_;
  int64_t batches_;
  sphere_span* spans_ = nullptr;
  uint32_t* list_ = nullptr;
  uint32_t* first_ = nullptr;
  uint32_t* fill_ = nullptr;
  uint32_t* count_ = nullptr;       // per batch of the run: its list's length
  uint32_t* slot_start_ = nullptr;  // per batch b: b * slot_
  const uint32_t* start_ = nullptr; // per batch of the run: its list's first entry (first_ or slot_start_)
  size_t slot_ = 0;                 // entries a slot holds (0: no slots)
  size_t kept_ = 0;
  int64_t b0_ = 0;
};

}  // namespace raycast
