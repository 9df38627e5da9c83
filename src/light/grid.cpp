#include "light/grid.h"

#include "light/key_sort.h"
#include "light/lanes.h"
#include "simd/cpu.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace raycast {
namespace {

constexpr double margin = 0x1p-16;       // grid units: the widening of each sphere's box (grid.h)
constexpr size_t max_references = size_t(1) << 31;

struct placed {  // a sphere (x y z r) and its index in the scene
  float s[4];
  uint32_t k;
};

// The cells sphere (x, y, z, r) (grid units) overlaps, per axis [c0, c1].
struct cell_range {
  int c0[3], c1[3];
  size_t count() const { return size_t(c1[0] - c0[0] + 1) * size_t(c1[1] - c0[1] + 1) * size_t(c1[2] - c0[2] + 1); }
};

}  // namespace

sphere_grid::sphere_grid(const scene& s, bool cells, int threads) : threads_(std::max(threads, 1)) {
  const size_t n = s.sphere_count();
  if (n == 0) return;
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = std::numeric_limits<double>::infinity(), hi[a] = -lo[a];
#pragma omp parallel for schedule(static) num_threads(threads_) reduction(min : lo[:3]) reduction(max : hi[:3])
  for (size_t k = 0; k < n; ++k) {
    const raycast::sphere sp = s.sphere_at(k);
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], sp.center[a] - sp.radius);
      hi[a] = std::max(hi[a], sp.center[a] + sp.radius);
    }
  }
  double half = 0;
  for (int a = 0; a < 3; ++a) {
    origin[a] = lo[a] * 0.5 + hi[a] * 0.5;
    half = std::max(half, hi[a] - origin[a]);
  }
  std::frexp(half, &scale_exp);  // half < 2^scale_exp
  const double unit = std::ldexp(1.0, -scale_exp);  // a power of two: the products are exact
  spheres_.resize(n * 4);
  // The cross-section summed by blocks of 2^16 spheres, in their order: the
  // same sum on any number of threads.
  std::vector<double> block((n + 0xffff) >> 16);
#pragma omp parallel for schedule(static) num_threads(threads_)
  for (size_t b = 0; b < block.size(); ++b) {
    double sum = 0;  // grid units
    for (size_t k = b << 16; k < std::min(n, (b + 1) << 16); ++k) {
      const raycast::sphere sp = s.sphere_at(k);
      for (int a = 0; a < 3; ++a) spheres_[k * 4 + a] = float((sp.center[a] - origin[a]) * unit);
      spheres_[k * 4 + 3] = float(sp.radius * unit);
      sum += double(spheres_[k * 4 + 3]) * double(spheres_[k * 4 + 3]);
    }
    block[b] = sum;
  }
  double cross_section = 0, volume = 1;
  for (double x : block) cross_section += x;
  for (int a = 0; a < 3; ++a) volume *= std::ldexp(hi[a] - lo[a], -scale_exp);
  cross_section *= 3.14159265358979323846;
  free_path_ = cross_section > 0 ? volume / cross_section / std::cbrt(volume / double(n))
                                 : std::numeric_limits<double>::infinity();
  if (cells) build_cells(lo, hi);
}

double sphere_grid::typical_radius() const {
  const size_t n = size(), step = n / 4096 + 1;
  std::vector<float> r;
  for (size_t k = 0; k < n; k += step) r.push_back(at(uint32_t(k))[3]);
  if (r.empty()) return 0;
  std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
  return r[r.size() / 2];
}

void sphere_grid::build_cells(const double lo[3], const double hi[3]) {
  const size_t n = size();
  // Grid units: the box lies within [-1, 1]. About one cell per sphere.
  double size[3], volume = 1;
  for (int a = 0; a < 3; ++a) {
    lo_[a] = float(std::ldexp(lo[a] - origin[a], -scale_exp) - 2 * margin);
    size[a] = std::ldexp(hi[a] - lo[a], -scale_exp) + 4 * margin;
    volume *= size[a];
  }
  double h = std::max(std::cbrt(volume / double(n)), 2 * typical_radius());
  const auto range_of = [&](size_t k) {
    cell_range r;
    const float* sp = at(uint32_t(k));  // by position
    const double inv = 1.0 / h;
    for (int a = 0; a < 3; ++a) {  // every coordinate is above lo_: int() is floor()
      const double x0 = (double(sp[a]) - sp[3] - margin - lo_[a]) * inv, x1 = (double(sp[a]) + sp[3] + margin - lo_[a]) * inv;
      r.c0[a] = std::clamp(int(x0), 0, dims_[a] - 1);
      r.c1[a] = std::clamp(int(x1), 0, dims_[a] - 1);
    }
    return r;
  };
  size_t listings = 0;  // each sphere's count capped, so that the sum cannot wrap
  for (;;) {  // coarser until the references fit
    for (int a = 0; a < 3; ++a) dims_[a] = int(std::clamp(std::ceil(size[a] / h), 1.0, double(1 << 20)));
    size_t total = 0;
#pragma omp parallel for schedule(static) num_threads(threads_) reduction(+ : total)
    for (size_t k = 0; k < n; ++k) total += std::min(range_of(k).count(), max_references + 1);
    listings = total;
    if (total <= max_references && total <= 64 * n + 4096) break;
    h *= 2;
  }
  h_ = float(h);
  inv_h_ = float(1.0 / h);
  for (int a = 0; a < 3; ++a) hi_[a] = lo_[a] + float(dims_[a]) * h_;
  const size_t cells = size_t(dims_[0]) * size_t(dims_[1]) * size_t(dims_[2]);
  const auto each_cell = [&](const cell_range& r, auto&& f) {
    for (int z = r.c0[2]; z <= r.c1[2]; ++z)
      for (int y = r.c0[1]; y <= r.c1[1]; ++y)
        for (int x = r.c0[0]; x <= r.c1[0]; ++x) f(size_t(x) + size_t(dims_[0]) * (size_t(y) + size_t(dims_[1]) * size_t(z)));
  };
  sort_by_home_cell(h);
  // Each sphere (by position, so by home cell) in the other cells it
  // overlaps, grouped by cell (ascending within each): a run of home cells a
  // thread.
  const int parts = threads_;
  const auto each_foreign = [&](int part, auto&& f) {
    const size_t end = part_begin(cells, part + 1, parts);  // computed once: a division
    for (size_t home = part_begin(cells, part, parts); home < end; ++home)
      for (uint32_t p = home_[home]; p < home_[home + 1]; ++p)
        each_cell(range_of(p), [&](size_t c) {
          if (c != home) f(c, p);
        });
  };
  key_sort<uint32_t> sort(cells, listings - n, parts);
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int part = 0; part < parts; ++part) each_foreign(part, [&](size_t c, uint32_t) { sort.count(part, c); });
  sort.start(refs_);
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int part = 0; part < parts; ++part) each_foreign(part, [&](size_t c, uint32_t p) { sort.put(part, c, p); });
  sort.finish(first_, parts);
  occupied_.assign((cells + 63) / 64, 0);
  for (size_t c = 0; c < cells; ++c)
    if (first_[c + 1] != first_[c] || home_[c + 1] != home_[c]) occupied_[c >> 6] |= uint64_t(1) << (c & 63);
}

// The spheres stored in the order of the cells their centres lie in (a
// stable counting sort, light/key_sort.h), rank_ mapping scene indices to
// positions, home_ each cell's first.
void sphere_grid::sort_by_home_cell(double h) {
  const size_t n = size(), cells = size_t(dims_[0]) * size_t(dims_[1]) * size_t(dims_[2]);
  out_of_order_array<uint32_t> home(n);
  const int parts = threads_;  // the spheres in one run a thread, the same runs for both passes
  const auto run = [&](int p, auto&& f) {
    const size_t end = part_begin(n, p + 1, parts);  // computed once: a division
    for (size_t k = part_begin(n, p, parts); k < end; ++k) f(k);
  };
  key_sort<placed> sort(cells, n, parts);
  const double inv = 1.0 / h;
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int p = 0; p < parts; ++p)
    run(p, [&](size_t k) {
      const float* s = &spheres_[k * 4];
      size_t c = 0, stride = 1;
      for (int a = 0; a < 3; ++a) {
        c += size_t(std::clamp(int((double(s[a]) - lo_[a]) * inv), 0, dims_[a] - 1)) * stride;
        stride *= size_t(dims_[a]);
      }
      home[k] = uint32_t(c);
      sort.count(p, c);
    });
  filled_later_array<placed> sorted;
  sort.start(sorted);
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int p = 0; p < parts; ++p)
    run(p, [&](size_t k) {
      sort.put(p, home[k], {{spheres_[k * 4], spheres_[k * 4 + 1], spheres_[k * 4 + 2], spheres_[k * 4 + 3]}, uint32_t(k)});
    });
  home = {};
  sort.finish(home_, parts);
  rank_.resize(n);
#pragma omp parallel for schedule(static) num_threads(parts)
  for (size_t p = 0; p < n; ++p) {
    for (int a = 0; a < 4; ++a) spheres_[p * 4 + a] = sorted[p].s[a];
    rank_[sorted[p].k] = uint32_t(p);
  }
}

// Amanatides and Woo's walk over the cells of the segment o + t d, t in
// [t0, t1] (within the grid's box); the boundaries' t in double, so that a
// sum of thousands of steps drifts by far less than the spheres' widening.
struct sphere_grid::walk {
  int c[3], dims[3];
  ptrdiff_t move[3], cell = 0;
  double next[3], delta[3], end;

  walk(const sphere_grid& g, const float o[3], const float d[3], float t0, float t1) : end(t1) {
    const ptrdiff_t stride[3] = {1, ptrdiff_t(g.dims_[0]), ptrdiff_t(g.dims_[0]) * g.dims_[1]};
    for (int a = 0; a < 3; ++a) {
      dims[a] = g.dims_[a];
      const float p = (o[a] + t0 * d[a] - g.lo_[a]) * g.inv_h_;
      c[a] = p <= 0.0f ? 0 : std::min(int(p), dims[a] - 1);
      cell += c[a] * stride[a];
      move[a] = d[a] > 0.0f ? stride[a] : -stride[a];
      if (d[a] == 0.0f) {
        next[a] = delta[a] = std::numeric_limits<double>::infinity();
        continue;
      }
      const double inv = 1.0 / double(d[a]);
      next[a] = (double(g.lo_[a]) + double(c[a] + (d[a] > 0.0f)) * double(g.h_) - double(o[a])) * inv;
      delta[a] = double(g.h_) * std::abs(inv);
    }
  }
  // To the next cell; false where the segment or the grid ends first.
  bool step() {
    // Each axis's step spelled out, so that next[] stays in registers.
    if (next[0] < next[1]) return next[0] < next[2] ? step_along<0>() : step_along<2>();
    return next[1] < next[2] ? step_along<1>() : step_along<2>();
  }
  template <int a>
  bool step_along() {
    if (next[a] > end) return false;
    c[a] += move[a] > 0 ? 1 : -1;
    if (unsigned(c[a]) >= unsigned(dims[a])) return false;
    cell += move[a];
    next[a] += delta[a];
    return true;
  }
};

bool sphere_grid::occluded(const float o[3], const float d[3], float tmax, uint32_t skip_index) const {
  if (home_.empty()) return false;
  const uint32_t skip = skip_index < size() ? position(skip_index) : skip_index;
  // The segment clipped to the grid's box (a hit point starts inside it:
  // no clipping, the walk ends where it leaves the box).
  float t0 = 0.0f, t1 = tmax;
  bool inside = true;
  for (int a = 0; a < 3; ++a) inside = inside && o[a] >= lo_[a] && o[a] < hi_[a];
  for (int a = 0; a < 3 && !inside; ++a) {
    if (d[a] == 0.0f) {
      if (o[a] < lo_[a] || o[a] > hi_[a]) return false;
      continue;
    }
    float ta = (lo_[a] - o[a]) / d[a], tb = (hi_[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1)) return false;
  walk w(*this, o, d, t0, t1);
  if (t1 - t0 > 4 * h_) return far_occluded(w, o, d, tmax, skip);
  do {
    if (occupied_[size_t(w.cell) >> 6] >> (w.cell & 63) & 1u && cell_occluded(size_t(w.cell), o, d, tmax, skip))
      return true;
  } while (w.step());
  return false;
}

const std::vector<int>& sphere_grid::lane_widths() {
  static const std::vector<int> widths = [] {
    std::vector<int> w{4};
#if defined(RAYCAST_LIGHT_W8)
    if (cpu().avx2) w.push_back(8);
#endif
    return w;
  }();
  return widths;
}

uint32_t sphere_grid::occluded(const float o[3], const float (*d)[3], int m, float tmax, uint32_t skip_index,
                               int lanes) const {
  bool inside = !home_.empty();
  for (int a = 0; a < 3; ++a) inside = inside && o[a] >= lo_[a] && o[a] < hi_[a];
  uint32_t blocked = 0;
  if (!inside || !walks_in_lanes()) {  // from outside, or coarse: one at a time
    for (int l = 0; l < m; ++l) blocked |= uint32_t(occluded(o, d[l], tmax, skip_index)) << l;
    return blocked;
  }
  const uint32_t skip = skip_index < size() ? position(skip_index) : skip_index;
#if defined(RAYCAST_LIGHT_W8)
  static const int widest = lane_widths().back();  // 8 only where the CPU runs AVX2
  if (widest == 8 && lanes != 4) return lanes_occluded<8>(o, d, m, tmax, skip);
#else
  (void)lanes;  // four lanes alone in this build
#endif
  return lanes_occluded<4>(o, d, m, tmax, skip);
}

// A walk of more than a few cells: the occupied cells ahead gathered 8 at a
// time, then tested together (cells_occluded), so that the misses of a long
// walk overlap instead of following one another (unbounded rays through
// 10^6 spheres: half the time).
bool sphere_grid::far_occluded(walk& w, const float o[3], const float d[3], float tmax, uint32_t skip) const {
  for (bool more = true; more;) {
    size_t found[ahead];
    int m = 0;
    while (m < ahead && more) {
      const size_t cell = size_t(w.cell);
      if (occupied_[cell >> 6] >> (cell & 63) & 1u) {
        found[m++] = cell;
        __builtin_prefetch(&home_[cell]);
        __builtin_prefetch(&first_[cell]);
      }
      more = w.step();
    }
    read_ahead(found, m);
    if (m > 0 && cells_occluded(found, m, o, d, tmax, skip)) return true;
  }
  return false;
}

// Prefetches the spheres and references of the occupied cells found[0 ..
// m), whose home_ and first_ entries were prefetched as they were found.
void sphere_grid::read_ahead(const size_t* found, int m) const {
  for (int i = 0; i < m; ++i) {
    const uint32_t h0 = home_[found[i]], h1 = home_[found[i] + 1];
    __builtin_prefetch(at(h0));
    __builtin_prefetch(at(std::max(h0, std::min(h1, h0 + 8) - 1)));  // a run of up to 8: its last line too
    __builtin_prefetch(refs_.data() + first_[found[i]]);
  }
}

// Whether a sphere of the occupied cells found[0 .. m) (m <= ahead, read
// ahead) but skip blocks the segment. The cells' spheres are tested from
// one list (listed()), not in a loop over each cell's two runs, whose
// lengths the walk cannot predict (light/README.md: a sixth less time where
// the grid stays in the cache, 10^5 spheres; a twentieth at 10^6), four at
// a time (any_blocks).
bool sphere_grid::cells_occluded(const size_t* found, int m, const float o[3], const float d[3], float tmax,
                                 uint32_t skip) const {
  uint32_t list[2 * ahead * 8 + lanes::width];  // listed() writes 8 a cell (twice the room m needs); any_blocks() pads
  int n = 0;
  for (int i = 0; i < m; ++i) {
    const int k = listed(found[i], list + n);
    if (k >= 0) n += k;
    else if (long_cell_occluded(found[i], o, d, tmax, skip)) return true;  // a longer run: listed alone
  }
  return n > 0 && any_blocks(list, n, o, d, tmax, skip);
}

// cell_occluded() for a cell with a run of more than 4 spheres: its
// spheres listed, 64 at a time, and tested four at a time (any_blocks).
bool sphere_grid::long_cell_occluded(size_t c, const float o[3], const float d[3], float tmax, uint32_t skip) const {
  constexpr int most = 64;
  uint32_t list[most + lanes::width];
  int n = 0;
  const auto add = [&](uint32_t p) {
    list[n++] = p;
    if (n < most) return false;
    n = 0;
    return any_blocks(list, most, o, d, tmax, skip);
  };
  for (uint32_t p = home_[c]; p < home_[c + 1]; ++p)
    if (add(p)) return true;
  for (uint32_t e = first_[c]; e < first_[c + 1]; ++e)
    if (add(refs_[e])) return true;
  return n > 0 && any_blocks(list, n, o, d, tmax, skip);
}

// Whether any sphere at positions list[0 .. n) but skip blocks the segment:
// blocks() four spheres at a time, one a vector lane (light/lanes.h), the
// same float operations in the same order lane by lane, so the same bits.
// list has room for n rounded up to 4; the tail repeats list[n - 1].
bool sphere_grid::any_blocks(uint32_t* list, int n, const float o[3], const float d[3], float tmax, uint32_t skip) const {
  using lanes::fvec;
  using lanes::ivec;
  for (int i = n; i % lanes::width != 0; ++i) list[i] = list[n - 1];
  const fvec dir[3] = {lanes::splat(d[0]), lanes::splat(d[1]), lanes::splat(d[2])};
  for (int i = 0; i < n; i += lanes::width) {
    const float *s0 = at(list[i]), *s1 = at(list[i + 1]), *s2 = at(list[i + 2]), *s3 = at(list[i + 3]);
    const fvec s[4] = {fvec{s0[0], s1[0], s2[0], s3[0]}, fvec{s0[1], s1[1], s2[1], s3[1]},
                       fvec{s0[2], s1[2], s2[2], s3[2]}, fvec{s0[3], s1[3], s2[3], s3[3]}};
    const ivec hit = lanes::blocks_in_lanes(o, dir, s, tmax);
    const ivec other = {list[i] != skip, list[i + 1] != skip, list[i + 2] != skip, list[i + 3] != skip};
    if (lanes::bits_of(hit & -other) != 0) return true;
  }
  return false;
}

}  // namespace raycast
