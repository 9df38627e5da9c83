#include "light/far/shadow_bins.h"

#include "light/blocks.h"
#include "light/far/key_sort.h"
#include "light/frame.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace raycast {
namespace {

constexpr float margin = 0x1p-20f;  // grid units: far above a shadow ray's rounding
constexpr size_t max_entries = size_t(1) << 31;

float dot(const float a[3], const float* b) { return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]; }

// A reach as an unsigned integer of the same order (-0 before +0).
uint32_t reach_key(float reach) {
  uint32_t b;
  std::memcpy(&b, &reach, sizeof b);
  return (b >> 31) ? ~b : b | 0x80000000u;
}

// A cell's list in the order of reach, ties by position, sorted while its
// band is in the cache (light/key_sort.h). Stable, as the list comes in the
// order of position. A short list: an
// insertion sort on the keys, the entries moved with them; a longer one:
// each entry's key and place sorted as one integer (past 96 entries a radix
// sort of the key's bytes, a byte every key shares skipped), then the
// entries moved.
void sort_by_reach(shadow_bins::entry* begin, shadow_bins::entry* end) {
  const size_t m = size_t(end - begin);
  if (m <= 16) {
    uint32_t key[16];
    for (size_t i = 0; i < m; ++i) {
      const shadow_bins::entry e = begin[i];
      const uint32_t k = reach_key(e.reach);
      size_t j = i;
      for (; j > 0 && k < key[j - 1]; --j) key[j] = key[j - 1], begin[j] = begin[j - 1];
      key[j] = k, begin[j] = e;
    }
    return;
  }
  thread_local std::vector<uint64_t> key, next;
  thread_local std::vector<shadow_bins::entry> was;
  key.resize(m), next.resize(m);
  for (size_t i = 0; i < m; ++i) key[i] = uint64_t(reach_key(begin[i].reach)) << 32 | i;
  if (m <= 96) std::sort(key.begin(), key.end());
  for (int shift = 32; shift < 64 && m > 96; shift += 8) {
    uint32_t count[257] = {};
    for (uint64_t q : key) ++count[((q >> shift) & 0xffu) + 1];
    if (std::find(count + 1, count + 257, uint32_t(m)) != count + 257) continue;
    for (int d = 0; d < 256; ++d) count[d + 1] += count[d];
    for (uint64_t q : key) next[count[(q >> shift) & 0xffu]++] = q;
    key.swap(next);
  }
  was.assign(begin, end);
  for (size_t i = 0; i < m; ++i) begin[i] = was[uint32_t(key[i])];
}

}  // namespace

shadow_bins::shadow_bins(const sphere_bvh& spheres, const float light[3], int threads)
    : spheres_(&spheres), threads_(std::max(threads, 1)) {
  for (int k = 0; k < 3; ++k) l_[k] = light[k];
  frame_about(l_, u_, v_);  // the plane's axes
  const size_t n = spheres.size();
  if (n == 0) return;
  // The classes' radii, each rounded up to a float: the widest the largest
  // sphere's own.
  disc_[0] = spheres.max_radius() + margin;
  for (int c = 1; c < 256; ++c) {
    const double want = double(disc_[0]) * std::exp2(-c / 16.0);
    disc_[c] = float(want);
    if (double(disc_[c]) < want) disc_[c] = std::nextafter(disc_[c], std::numeric_limits<float>::infinity());
  }
  // The discs' bounds across L.
  float lo0 = std::numeric_limits<float>::infinity(), lo1 = lo0, hi0 = -lo0, hi1 = -lo0;
#pragma omp parallel for schedule(static) num_threads(threads_) reduction(min : lo0, lo1) reduction(max : hi0, hi1)
  for (size_t k = 0; k < n; ++k) {
    const entry e = entry_of(uint32_t(k));
    const float r = radius(e);
    lo0 = std::min(lo0, e.u - r - margin);
    lo1 = std::min(lo1, e.v - r - margin);
    hi0 = std::max(hi0, e.u + r + margin);
    hi1 = std::max(hi1, e.v + r + margin);
  }
  lo_[0] = lo0, lo_[1] = lo1;
  const float hi[2] = {hi0, hi1};
  bin(hi);
}

// The smallest class whose radius is at least r: the largest c with
// disc_[c] >= r (the table falls with c), 0 for the largest sphere.
uint32_t shadow_bins::radius_class(float r) const {
  uint32_t lo = 0, hi = 255;  // disc_[lo] >= r
  if (disc_[hi] >= r) return hi;
  while (hi - lo > 1) {
    const uint32_t mid = (lo + hi) / 2;
    (disc_[mid] >= r ? lo : hi) = mid;
  }
  return lo;
}

float shadow_bins::radius(const entry& e) const {
  uint32_t b;
  std::memcpy(&b, &e.reach, sizeof b);
  return disc_[b & 0xffu];
}

shadow_bins::entry shadow_bins::entry_of(uint32_t p) const {
  const sphere4 sp = spheres_->at(p);
  const float* s = sp.v;
  const float reach = ((dot(l_, s) + s[3]) + margin) + reach_offset;  // above 2: a positive float's bits
  uint32_t b;
  std::memcpy(&b, &reach, sizeof b);
  b = ((b + 0xffu) & ~0xffu) | radius_class(s[3] + margin);  // rounded up, so still past the sphere
  entry e{0.0f, p, dot(u_, s), dot(v_, s)};
  std::memcpy(&e.reach, &b, sizeof b);
  return e;
}

void shadow_bins::bin(const float hi[2]) {
  const size_t n = spheres_->size();
  // Cells twice a typical sphere's diameter: a disc lies in about 2.25 of
  // them (4 at one diameter, for a tenth more time and 35 bytes a sphere
  // more); the entries are each cell's candidates, whose test is the same.
  double g = std::max(std::sqrt(double(hi[0] - lo_[0]) * double(hi[1] - lo_[1]) / double(n)), 4 * spheres_->typical_radius());
  double inv = 1.0 / g;
  const auto range_of = [&](const entry& e, int r[4]) {  // the cells of a disc: x0, x1, y0, y1
    const float p[2] = {e.u, e.v};
    const double er = radius(e);
    for (int a = 0; a < 2; ++a) {
      r[2 * a] = std::clamp(int((double(p[a]) - er - lo_[a]) * inv), 0, dims_[a] - 1);
      r[2 * a + 1] = std::clamp(int((double(p[a]) + er - lo_[a]) * inv), 0, dims_[a] - 1);
    }
  };
  const auto each_cell = [&](const entry& e, auto&& f) {  // ascending
    int r[4];
    range_of(e, r);
    for (int y = r[2]; y <= r[3]; ++y)
      for (int x = r[0]; x <= r[1]; ++x) f(size_t(x) + size_t(dims_[0]) * size_t(y));
  };
  const size_t most = std::min(max_entries, 64 * n + 4096);
  // The spheres in one run a thread, the same runs for counting and filling.
  const int parts = threads_;
  const auto run = [&](int p, auto&& f) {
    const size_t end = part_begin(n, p + 1, parts);  // computed once: a division a sphere was 10 % of counting
    for (size_t k = part_begin(n, p, parts); k < end; ++k) f(uint32_t(k));
  };
  for (;;) {  // each cell's count; coarser until the entries fit (a try stops once they cannot)
    for (int a = 0; a < 2; ++a) dims_[a] = int(std::clamp(std::ceil((hi[a] - lo_[a]) * inv), 1.0, double(1 << 15)));
    const size_t cells = size_t(dims_[0]) * size_t(dims_[1]);
    key_sort<entry, decltype(each_cell)> sort(cells, n * 9 / 4, parts, each_cell);
    size_t total = 0;
#pragma omp parallel for schedule(static, 1) num_threads(parts) reduction(+ : total)
    for (int p = 0; p < parts; ++p) {
      size_t mine = 0;
      run(p, [&](uint32_t k) {
        if (mine <= most) mine += sort.count(p, entry_of(k));
      });
      total += mine;
    }
    if (total > most) {
      g *= 2, inv = 1.0 / g;
      continue;
    }
    inv_g_ = float(inv);
    // Each cell's list, in the order of position, then sorted by reach. Each
    // entry is computed again from its sphere (the same floats).
    sort.start(entries_);
#pragma omp parallel for schedule(static, 1) num_threads(parts)
    for (int p = 0; p < parts; ++p) run(p, [&](uint32_t k) { sort.put(p, entry_of(k)); });
    sort.finish(first_, sort_by_reach, parts);
    return;
  }
}

size_t shadow_bins::longest_list() const {
  size_t most = 0;
  for (size_t c = 0; c + 1 < first_.size(); ++c) most = std::max<size_t>(most, first_[c + 1] - first_[c]);
  return most;
}

shadow_bins::query shadow_bins::locate(const float p[3]) const {
  query q{none, dot(u_, p), dot(v_, p), dot(l_, p) + reach_offset};
  const float pu = (q.u - lo_[0]) * inv_g_, pv = (q.v - lo_[1]) * inv_g_;
  if (entries_.empty() || !(pu >= 0.0f && pv >= 0.0f)) return q;  // outside every disc (or NaN)
  const int x = int(pu), y = int(pv);
  if (x < dims_[0] && y < dims_[1]) q.cell = size_t(x) + size_t(dims_[0]) * size_t(y);
  return q;
}

void shadow_bins::prefetch(const query& q, int step) const {
  if (q.cell == none) return;
  if (step == 0) __builtin_prefetch(&first_[q.cell]);
  else if (first_[q.cell + 1] > first_[q.cell]) __builtin_prefetch(entries_.data() + first_[q.cell + 1] - 1);
}

bool shadow_bins::occluded(const query& q, const float p[3], uint32_t skip) const {
  if (q.cell == none) return false;
  const size_t c = q.cell;
  const float u = q.u, v = q.v, depth = q.depth;
  const entry* begin = entries_.data() + first_[c];
  const entry* end = entries_.data() + first_[c + 1];
  // The spheres that reach past P along L, from the far end of the list
  // down to the first that ends before P (it and the rest lie wholly
  // behind it): no search, and each of them is tested anyway.
  const float inf = std::numeric_limits<float>::infinity();
  for (const entry* e = end; e != begin && e[-1].reach >= depth;) {
    --e;
    const float du = u - e->u, dv = v - e->v, r = radius(*e);
    if (du * du + dv * dv > r * r) continue;  // the ray passes outside its disc
    if (e->k != skip && blocks_one(p, l_, spheres_->at(e->k).v, inf)) return true;
  }
  return false;
}

}  // namespace raycast
