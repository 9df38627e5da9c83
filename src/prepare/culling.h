// Culling: which spheres the rays of each row, and of each batch of a row, can hit. Compiled once
// (not per instruction set); the kernels only read what it builds. Two levels, so a frame of N
// spheres costs O(N + entries) whatever the threads or bands:
//  - per frame, a row index: for every image row, the spheres whose rows (sphere_rows) cover it,
//    in the float scene's order, each with the columns it may touch; in a depth-ordered scene
//    without the spheres nearer ones surely hide (occlusion, culling.cpp). 8 bytes a row and an
//    entry; while built, 20 a sphere (and with occlusion a byte a pixel).
//  - per row, while it is rendered: the listed spheres' batches (from their columns, or a tall
//    sphere's exact test), turned into one list per batch of columns (batch_culler), per thread.
// Every test is conservative: the margins are hundreds of times the float intersection's rounding,
// so leaving a sphere out never changes a pixel (tests/test_culling.cpp checks every hit).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "prepare/float_scene.h"
#include "memory/arrays.h"

namespace raycast {

// A sphere some ray of a row may hit, and the batches lo .. hi (inclusive) whose rays may.
struct sphere_span {
  uint32_t sphere;
  int32_t lo, hi;
};

// The spheres a ray of the row with this sv may hit, in order, with their batches, into out (room
// for every candidate); returns how many. A row's rays lie in the plane through the origin spanned
// by centre + sv vertical and horizontal, and a column's ray can hit only where its line comes
// within the radius of the centre (a quadratic in the column). With candidates, only those; with
// spread (pixel_spread), for the pixels' whole squares of samples (radii widened by spread |f|).
size_t spheres_in_row(const float_scene& f, float sv, int batch, sphere_span* out,
                      const uint32_t* candidates = nullptr, size_t n_candidates = 0,
                      double spread = 0.0);

// The rows j (0 at the bottom) whose plane may come near sphere k (a superset); false when none.
bool sphere_rows(const float_scene& f, uint32_t k, int64_t& j_lo, int64_t& j_hi, double spread = 0.0);

// A sphere in a row of the row index, with the columns its box may touch, lo << shift ..
// (hi << shift) + 2^shift - 1; lo = tall for a sphere tested exactly in each row. shift (the
// index's) is 0 up to 65,535 columns; wider images round boxes out to 2^shift columns.
struct row_entry {
  uint32_t sphere;
  uint16_t lo, hi;
  static constexpr uint16_t tall = 0xffff;
};

// Per frame: for each image row r (0 at the top, as image_band), the spheres whose rows include it.
struct row_index {
  std::vector<uint64_t> first;  // list[first[r] .. first[r + 1]) for row r
  filled_array<row_entry> list;  // 8 bytes per entry
  size_t most = 0;                // the longest row's count
  size_t hidden = 0;              // spheres left out as hidden by nearer ones (occlusion)
  int shift = 0;                  // the entries' column unit, 2^shift

  // Built with up to `threads` threads; the same bytes for any count.
  static row_index build(const float_scene& f, double spread, int threads);
};

// Per thread, per row: the lists of the spheres each batch of the row may hit. Raw memory and
// out-of-line functions only: the per-instruction-set kernels must instantiate no standard-library
// template. Without memory (ok() false) a kernel tests every sphere, slow but right.
class batch_culler {
 public:
  // For a row index of at most `most` candidates a row and column unit 2^shift.
  batch_culler(const float_scene& f, size_t most, int shift, int batch, double spread);
  ~batch_culler();
  batch_culler(const batch_culler&) = delete;
  batch_culler& operator=(const batch_culler&) = delete;
  bool ok() const { return spans_ != nullptr; }

  // The row with this sv from its index entries; returns how many spheres it keeps.
  size_t row(float sv, const row_entry* entries, size_t count);
  // How many batches one run of lists may cover (within the lists' memory).
  int64_t run_length() const;
  // The lists of the row's batches [b0, b1) (b1 - b0 <= run_length()).
  void build(int64_t b0, int64_t b1);
  // Batch b's spheres (b in the last build's run; list(b) only where tests(b) > 0).
  const uint32_t* list(int64_t b) const { return list_ + start_[b - b0_]; }
  size_t tests(int64_t b) const { return kept_ == 0 ? 0 : count_[b - b0_]; }

 private:
  void release();
  // The common case, in one pass: each batch's list in its own slot of slot_ entries; false where
  // a slot would overflow (row() then writes over it).
  bool row_in_slots(float sv, const row_entry* entries, size_t count);
  bool slotted_ = false;  // the row's lists are in slots: build has nothing to do
  // The least list entries one run may hold (else four a candidate).
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
