#include "light/far/nodes.h"

#include <algorithm>
#include <limits>

namespace raycast {
namespace {

constexpr uint32_t task_size = 1u << 15;  // ranges above it are built as tasks

struct child {
  uint32_t ref = bvh_ref::empty;
  float box[6];
};

bvh_node empty_node() {
  bvh_node n;
  for (int a = 0; a < 3; ++a)
    for (int s = 0; s < 8; ++s) n.box[a][s] = std::numeric_limits<float>::infinity(), n.box[a + 3][s] = -n.box[a][s];
  for (uint32_t& c : n.child) c = bvh_ref::empty;
  return n;
}

// One builder a task: its nodes (indices local to them), its leaves.
class builder {
 public:
  builder(const octree_input& in, bool tasks) : in_(in), tasks_(tasks) {}
  octree_result result;

  child range(uint32_t a, uint32_t b, int shift) {
    if (b - a <= bvh_ref::most_in_leaf) return leaf(a, b);
    uint32_t cut[9];
    shift = split(a, b, shift, cut);
    const uint32_t at = uint32_t(result.nodes.size());
    result.nodes.push_back(empty_node());
    child kids[8];
    if (tasks_ && b - a > task_size) {
      in_tasks(cut, shift, kids);
    } else {
      for (int o = 0; o < 8; ++o)
        if (cut[o] < cut[o + 1]) kids[o] = range(cut[o], cut[o + 1], shift);
    }
    child me;
    me.ref = at;
    for (int a6 = 0; a6 < 3; ++a6) me.box[a6] = std::numeric_limits<float>::infinity(), me.box[a6 + 3] = -me.box[a6];
    bvh_node& node = result.nodes[at];
    for (int o = 0; o < 8; ++o) {
      if (kids[o].ref == bvh_ref::empty) continue;
      node.child[o] = kids[o].ref;
      for (int k = 0; k < 6; ++k) node.box[k][o] = kids[o].box[k];
      for (int k = 0; k < 3; ++k) me.box[k] = std::min(me.box[k], kids[o].box[k]);
      for (int k = 3; k < 6; ++k) me.box[k] = std::max(me.box[k], kids[o].box[k]);
    }
    return me;
  }

 private:
  uint32_t code(uint32_t p) const { return uint32_t(in_.keys[p] >> 32); }

  // The level (bit) [a, b)'s codes first differ at, and its children's
  // ranges cut[o] .. cut[o + 1]: by octant there, or in eight equal runs
  // where every code is the same (shift -1).
  int split(uint32_t a, uint32_t b, int shift, uint32_t cut[9]) const {
    while (shift >= 0 && ((code(a) >> shift) & 7u) == ((code(b - 1) >> shift) & 7u)) shift -= 3;
    if (shift < 0) {
      for (int o = 0; o <= 8; ++o) cut[o] = a + uint32_t(uint64_t(b - a) * uint64_t(o) / 8);
      return -1;
    }
    cut[0] = a;
    cut[8] = b;
    for (uint32_t o = 1; o < 8; ++o) {
      uint32_t lo = cut[o - 1], hi = b;  // the first position whose octant is o or more
      while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (((code(mid) >> shift) & 7u) < o) lo = mid + 1;
        else hi = mid;
      }
      cut[o] = lo;
    }
    return shift - 3;
  }

  child leaf(uint32_t a, uint32_t b) {
    child c;
    c.ref = bvh_ref::leaf(a, b - a);
    for (int k = 0; k < 3; ++k) c.box[k] = std::numeric_limits<float>::infinity(), c.box[k + 3] = -c.box[k];
    for (uint32_t p = a; p < b; ++p) {
      const float* s = in_.xyzr + size_t(p) * 4;
      for (int k = 0; k < 3; ++k) {
        c.box[k] = std::min(c.box[k], s[k] - s[3] - box_margin);
        c.box[k + 3] = std::max(c.box[k + 3], s[k] + s[3] + box_margin);
      }
    }
    return c;
  }

  // The children of a big range, each built by a task of its own, then
  // appended in order after this builder's nodes (their indices moved by
  // where they land).
  void in_tasks(const uint32_t cut[9], int shift, child kids[8]) {
    builder parts[8] = {{in_, true}, {in_, true}, {in_, true}, {in_, true},
                        {in_, true}, {in_, true}, {in_, true}, {in_, true}};
    for (int o = 0; o < 8; ++o) {
      if (cut[o] >= cut[o + 1]) continue;
#pragma omp task default(shared) firstprivate(o)
      kids[o] = parts[o].range(cut[o], cut[o + 1], shift);
    }
#pragma omp taskwait
    for (int o = 0; o < 8; ++o) {
      if (cut[o] >= cut[o + 1]) continue;
      const uint32_t base = uint32_t(result.nodes.size());
      for (bvh_node& n : parts[o].result.nodes) {
        for (uint32_t& c : n.child)
          if (!bvh_ref::is_leaf(c)) c += base;
        result.nodes.push_back(n);
      }
      if (!bvh_ref::is_leaf(kids[o].ref)) kids[o].ref += base;
    }
  }

  const octree_input& in_;
  bool tasks_;
};

}  // namespace

octree_result build_octree(const octree_input& in, int threads) {
  builder b(in, threads > 1);
  if (in.n == 0) return std::move(b.result);
  b.result.nodes.reserve(in.n / 8 + 64);  // mapped, not touched, beyond what is used
  child top;
#pragma omp parallel num_threads(std::max(threads, 1))
#pragma omp single
  top = b.range(0, in.n, 27);
  b.result.root = top.ref;
  // The leaves' count and volume in the nodes' order: the same sum on any number of threads.
  const auto add = [&](uint32_t ref, const float* box, int stride) {
    if (ref == bvh_ref::empty || !bvh_ref::is_leaf(ref)) return;
    ++b.result.leaves;
    b.result.leaf_volume += double(box[3 * stride] - box[0]) * double(box[4 * stride] - box[stride]) *
                            double(box[5 * stride] - box[2 * stride]);
  };
  if (bvh_ref::is_leaf(top.ref)) add(top.ref, top.box, 1);
  for (const bvh_node& n : b.result.nodes)
    for (int o = 0; o < 8; ++o) add(n.child[o], &n.box[0][o], 8);
  return std::move(b.result);
}

}  // namespace raycast
