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

sphere_bvh::sphere_bvh(const scene& s, int threads) {
  threads = std::max(threads, 1);
  if (s.sphere_count() == 0) return;
  frame_spheres(s, threads, leaf_);  // in the scene's order, until the leaves are filled
  sort_by_morton(leaf_, threads);
}

// origin, scale_exp and the spheres in that frame, in the scene's order
// (4 floats a sphere); the largest and a typical radius.
void sphere_bvh::frame_spheres(const scene& s, int threads, out_of_order_array<float>& out) {
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
  const double unit = std::ldexp(1.0, -scale_exp);  // a power of two: the products are exact
  out.resize(n * 4 + 8);
  float most = 0;
#pragma omp parallel for schedule(static) num_threads(threads) reduction(max : most)
  for (size_t k = 0; k < n; ++k) {
    const raycast::sphere sp = s.sphere_at(k);
    for (int a = 0; a < 3; ++a) out[k * 4 + a] = float((sp.center[a] - origin[a]) * unit);
    out[k * 4 + 3] = float(sp.radius * unit);
    most = std::max(most, out[k * 4 + 3]);
  }
  max_radius_ = most;
  const size_t step = n / 4096 + 1;
  std::vector<float> r;
  for (size_t k = 0; k < n; k += step) r.push_back(out[k * 4 + 3]);
  std::nth_element(r.begin(), r.begin() + ptrdiff_t(r.size() / 2), r.end());
  typical_radius_ = r[r.size() / 2];
}

// The spheres by position: sorted by the Morton code of their centres (ten
// bits an axis over the centres' bounding cube; ties in the scene's order),
// then the nodes over them.
void sphere_bvh::sort_by_morton(const out_of_order_array<float>& in, int threads) {
  const size_t n = in.size() / 4 - 2;
  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = std::numeric_limits<float>::infinity(), hi[a] = -lo[a];
  for (size_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], in[k * 4 + a]), hi[a] = std::max(hi[a], in[k * 4 + a]);
  const float side = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-30f});
  const float scale = 1023.0f / side;
  out_of_order_array<uint64_t> keys;
  keys.resize(n);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (size_t k = 0; k < n; ++k) {
    uint32_t code = 0;
    for (int a = 0; a < 3; ++a) code |= spread(uint32_t(std::clamp((in[k * 4 + a] - lo[a]) * scale, 0.0f, 1023.0f))) << a;
    keys[k] = uint64_t(code) << 32 | k;
  }
  radix_sort(keys, 32, 30, threads);
  xyzr_.resize(n * 4);
  rank_.resize(n);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (size_t p = 0; p < n; ++p) {
    const uint32_t k = uint32_t(keys[p]);
    for (int a = 0; a < 4; ++a) xyzr_[p * 4 + a] = in[size_t(k) * 4 + a];
    rank_[k] = uint32_t(p);
  }
  build_nodes(keys, threads);
  fill_leaves(threads);
}

// Each leaf's spheres as rows (bvh_view::leaf), leaf by leaf from the nodes.
void sphere_bvh::fill_leaves(int threads) {
  const size_t n = size();
  for (size_t i = n * 4; i < leaf_.size(); ++i) leaf_[i] = std::numeric_limits<float>::quiet_NaN();
  const auto fill = [&](uint32_t ref) {
    const uint32_t first = bvh_ref::first(ref), c = bvh_ref::count(ref);
    for (uint32_t i = 0; i < c; ++i)
      for (uint32_t a = 0; a < 4; ++a) leaf_[size_t(first) * 4 + a * c + i] = xyzr_[size_t(first + i) * 4 + a];
  };
  if (bvh_ref::is_leaf(root_)) fill(root_);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (size_t i = 0; i < nodes_.size(); ++i)
    for (uint32_t c : nodes_[i].child)
      if (c != bvh_ref::empty && bvh_ref::is_leaf(c)) fill(c);
}

void sphere_bvh::build_nodes(const out_of_order_array<uint64_t>& keys, int threads) {
  const octree_input in{keys.data(), xyzr_.data(), uint32_t(size())};
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
  v.xyzr = xyzr_.data();
  v.leaf = leaf_.data();
  v.max_r = max_radius_;
  return v;
}

}  // namespace raycast
