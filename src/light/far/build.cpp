// sphere_bvh's build: the spheres in the light's frame, sorted by their
// centres' Morton codes (far/radix_sort.h), then the octree over those codes
// (far/nodes.cpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "light/far/bvh.h"
#include "light/far/nodes.h"
#include "light/far/radix_sort.h"

namespace raycast {
namespace {

// Ten bits of v spread to every third bit (bit i to bit 3 i).
uint32_t spread(uint32_t v) {
  v &= 0x3ffu;
  v = (v | v << 16) & 0x030000ffu;
  v = (v | v << 8) & 0x0300f00fu;
  v = (v | v << 4) & 0x030c30c3u;
  v = (v | v << 2) & 0x09249249u;
  return v;
}

}  // namespace

sphere_bvh::sphere_bvh(const scene& s, int threads, bool open_nodes) {
  threads = std::max(threads, 1);
  if (s.sphere_count() == 0) return;
  frame(s, threads);
  survey(s, threads);
  sort_by_morton(s, threads, open_nodes || free_path_ <= open_free_path);
}

// A scene sphere in the light's frame (the same bits wherever it is made).
sphere4 sphere_bvh::in_frame(const raycast::sphere& sp) const {
  return {{float((sp.center[0] - origin[0]) * unit_), float((sp.center[1] - origin[1]) * unit_),
           float((sp.center[2] - origin[2]) * unit_), float(sp.radius * unit_)}};
}

// origin and scale_exp: the middle of the spheres' box, and the power of two
// that brings it into [-1, 1].
void sphere_bvh::frame(const scene& s, int threads) {
  const size_t n = s.sphere_count();
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = std::numeric_limits<double>::infinity(), hi[a] = -lo[a];
#pragma omp parallel for schedule(static) num_threads(threads) reduction(min : lo[:3]) reduction(max : hi[:3])
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
  unit_ = std::ldexp(1.0, -scale_exp);  // a power of two: in_frame's products are exact
  volume_ = 1;
  for (int a = 0; a < 3; ++a) volume_ *= std::ldexp(hi[a] - lo[a], -scale_exp);
}

// From the spheres in the light's frame: the largest and a typical radius,
// the free path, and the centres' box (for the Morton codes). The
// cross-section is summed by blocks of 2^16 spheres in their order: the same
// sum on any number of threads.
void sphere_bvh::survey(const scene& s, int threads) {
  const size_t n = s.sphere_count();
  float most = 0, lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = std::numeric_limits<float>::infinity(), hi[a] = -lo[a];
  std::vector<double> block((n + 0xffff) >> 16);
#pragma omp parallel for schedule(static) num_threads(threads) reduction(max : most) reduction(min : lo[:3]) \
    reduction(max : hi[:3])
  for (size_t b = 0; b < block.size(); ++b) {
    double sum = 0;
    for (size_t k = b << 16; k < std::min(n, (b + 1) << 16); ++k) {
      const sphere4 c = in_frame(s.sphere_at(k));
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
      most = std::max(most, c[3]);
      sum += double(c[3]) * double(c[3]);
    }
    block[b] = sum;
  }
  max_radius_ = most;
  for (int a = 0; a < 3; ++a) centre_lo_[a] = lo[a], centre_hi_[a] = hi[a];
  double cross_section = 0;
  for (double x : block) cross_section += x;
  cross_section *= 3.14159265358979323846;
  free_path_ = cross_section > 0 ? volume_ / cross_section / std::cbrt(volume_ / double(n))
                                 : std::numeric_limits<double>::infinity();
  const size_t step = n / 4096 + 1;
  std::vector<float> r;
  for (size_t k = 0; k < n; k += step) r.push_back(in_frame(s.sphere_at(k))[3]);
  std::nth_element(r.begin(), r.begin() + ptrdiff_t(r.size() / 2), r.end());
  typical_radius_ = r[r.size() / 2];
}

// The spheres by position: sorted by the Morton code of their centres (ten
// bits an axis over the centres' bounding cube; ties in the scene's order),
// then the nodes and leaves over them; without nodes, in the scene's order.
// The spheres in the frame (survey) are read in the codes' order, a
// few ahead of their use, and written in order: the build's peak memory is
// the keys, the spheres in both orders and the nodes.
void sphere_bvh::sort_by_morton(const scene& s, int threads, bool nodes) {
  const size_t n = s.sphere_count();
  out_of_order_array<uint64_t> keys;  // without nodes: none, the scene's order kept
  if (nodes) {
    const float side = std::max({centre_hi_[0] - centre_lo_[0], centre_hi_[1] - centre_lo_[1],
                                 centre_hi_[2] - centre_lo_[2], 1e-30f});
    const float scale = 1023.0f / side;
    keys.resize(n);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (size_t k = 0; k < n; ++k) {
      const sphere4 c = in_frame(s.sphere_at(k));
      uint32_t code = 0;
      for (int a = 0; a < 3; ++a)
        code |= spread(uint32_t(std::clamp((c[a] - centre_lo_[a]) * scale, 0.0f, 1023.0f))) << a;
      keys[k] = uint64_t(code) << 32 | k;
    }
    radix_sort(keys, 32, 30, threads);
  }
  out_of_order_array<float> sorted;
  sorted.resize(n * 4 + 8);
  rank_.resize(n);
  // Each sphere to its place, read in the scene's order and written out of
  // order (a store waits on nothing; a read out of order would).
#pragma omp parallel for schedule(static) num_threads(threads)
  for (size_t p = 0; p < n; ++p) rank_[nodes ? uint32_t(keys[p]) : p] = uint32_t(p);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (size_t k = 0; k < n; ++k) {
    const sphere4 c = in_frame(s.sphere_at(k));
    for (int a = 0; a < 4; ++a) sorted[size_t(rank_[k]) * 4 + a] = c[a];
  }
  for (size_t i = n * 4; i < sorted.size(); ++i) sorted[i] = std::numeric_limits<float>::quiet_NaN();
  if (nodes) build_nodes(keys, sorted, threads);
  else leaves_ = (n + 7) / 8;
  keys = {};
  fill_leaves(sorted, threads);
}

// Each leaf's spheres as rows (bvh_view::leaf), and each sphere's place in
// its leaf, leaf by leaf from the nodes: a leaf's spheres x y z r take the
// same floats as its rows, so each is turned in place.
void sphere_bvh::fill_leaves(out_of_order_array<float>& sorted, int threads) {
  const size_t n = size();
  place_.resize(n);
  const auto fill = [&](uint32_t ref) {
    const uint32_t first = bvh_ref::first(ref), c = bvh_ref::count(ref);
    float* at = &sorted[size_t(first) * 4];
    float was[4 * bvh_ref::most_in_leaf];
    std::copy(at, at + 4 * c, was);
    for (uint32_t i = 0; i < c; ++i) {
      for (uint32_t a = 0; a < 4; ++a) at[a * c + i] = was[i * 4 + a];
      place_[first + i] = uint8_t(i | (c - 1) << 3);
    }
  };
  if (nodes_.empty() && root_ == bvh_ref::empty) {  // no nodes: runs of eight
#pragma omp parallel for schedule(static) num_threads(threads)
    for (size_t first = 0; first < n; first += 8)
      fill(bvh_ref::leaf(uint32_t(first), uint32_t(std::min<size_t>(8, n - first))));
  }
  if (root_ != bvh_ref::empty && bvh_ref::is_leaf(root_)) fill(root_);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (size_t i = 0; i < nodes_.size(); ++i)
    for (uint32_t c : nodes_[i].child)
      if (c != bvh_ref::empty && bvh_ref::is_leaf(c)) fill(c);
  leaf_ = std::move(sorted);
}

void sphere_bvh::build_nodes(const out_of_order_array<uint64_t>& keys, const out_of_order_array<float>& sorted,
                             int threads) {
  const octree_input in{keys.data(), sorted.data(), uint32_t(size())};
  octree_result t = build_octree(in, threads);
  nodes_ = std::move(t.nodes);
  root_ = t.root;
  leaves_ = t.leaves;
  density_ = t.leaf_volume > 0 ? double(size()) / t.leaf_volume : std::numeric_limits<double>::infinity();
}

bvh_view sphere_bvh::view() const {
  bvh_view v;
  if (size() == 0) return v;
  v.nodes = nodes_.data();
  v.root = root_;
  v.leaf = leaf_.data();
  v.max_r = max_radius_;
  return v;
}

}  // namespace raycast
