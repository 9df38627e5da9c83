#include "light/far/nodes.h"

#include <algorithm>
#include <limits>
#include <vector>

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

// A range of at most task_size positions that the threads build apart.
struct job {
  uint32_t a, b;
  int shift;
  child top;
  out_of_order_array<bvh_node> nodes;  // indices local to them
};

// Builds [a, b) depth first. Where several threads build, it runs twice
// over the top of the tree: first to list the jobs (pass::plan), which the
// threads then build, then to join their nodes in the order one thread
// would have made them (pass::join). No OpenMP tasks: the build is one
// parallel loop over the jobs.
class builder {
 public:
  enum class pass { whole, plan, join };
  builder(const octree_input& in, pass p, std::vector<job>* jobs = nullptr) : in_(in), pass_(p), jobs_(jobs) {}
  octree_result result;

  child range(uint32_t a, uint32_t b, int shift) {
    if (pass_ != pass::whole && b - a <= task_size) return job_at(a, b, shift);
    if (b - a <= bvh_ref::most_in_leaf) return leaf(a, b);
    uint32_t cut[9];
    shift = split(a, b, shift, cut);
    const uint32_t at = uint32_t(result.nodes.size());
    result.nodes.push_back(empty_node());
    child kids[8];
    for (int o = 0; o < 8; ++o)
      if (cut[o] < cut[o + 1]) kids[o] = range(cut[o], cut[o + 1], shift);
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

  // plan: the job listed; join: its nodes appended after this builder's,
  // their indices moved by where they land.
  child job_at(uint32_t a, uint32_t b, int shift) {
    if (pass_ == pass::plan) {
      jobs_->push_back({a, b, shift, {}, {}});
      return {};
    }
    job& j = (*jobs_)[next_++];
    const uint32_t base = uint32_t(result.nodes.size());
    for (bvh_node& n : j.nodes) {
      for (uint32_t& c : n.child)
        if (!bvh_ref::is_leaf(c)) c += base;  // empty slots have the leaf bit
      result.nodes.push_back(n);
    }
    j.nodes = {};
    if (!bvh_ref::is_leaf(j.top.ref)) j.top.ref += base;
    return j.top;
  }

  const octree_input& in_;
  pass pass_;
  std::vector<job>* jobs_;
  size_t next_ = 0;
};

}  // namespace

octree_result build_octree(const octree_input& in, int threads) {
  const bool apart = threads > 1 && in.n > task_size;
  std::vector<job> jobs;
  if (apart) {
    builder(in, builder::pass::plan, &jobs).range(0, in.n, 27);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (size_t k = 0; k < jobs.size(); ++k) {
      builder w(in, builder::pass::whole);
      jobs[k].top = w.range(jobs[k].a, jobs[k].b, jobs[k].shift);
      jobs[k].nodes = std::move(w.result.nodes);
    }
  }
  builder b(in, apart ? builder::pass::join : builder::pass::whole, &jobs);
  if (in.n == 0) return std::move(b.result);
  b.result.nodes.reserve(in.n / 8 + 64);  // mapped, not touched, beyond what is used
  const child top = b.range(0, in.n, 27);
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
