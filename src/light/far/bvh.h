// The far field: a wide bounding-volume hierarchy over every sphere, the one
// structure every occlusion query of light/ asks (light/README.md). Eight
// children a node, each the spheres of one octant of its parent's Morton
// range (an octree over the spheres' centres, with tight boxes and the
// levels a range does not split on skipped); leaves of up to eight spheres,
// held inline, each leaf's spheres a row a coordinate, one after another in
// the centres' Morton order. A ray tests a node's eight boxes in one vector
// step, and a leaf's spheres in another.
//
// The spheres are kept in the light's frame: world minus `origin` (the
// middle of the spheres' bounding box), times 2^-scale_exp (a power of two
// that brings the box into [-1, 1]: exact, so a scene at 1e-20 or 1e20 gives
// the same float bits as at 1), rounded to float once. Each box holds its
// spheres widened by 2^-16 (grid units), far above the rounding of a box
// test, so no ray that meets a sphere misses the boxes around it.
//
// Memory: 16 bytes a sphere in the leaves' rows, 5 bytes a sphere for its
// position and its place in its leaf, and 224 bytes a node: about 30 bytes
// a sphere (and 16 more while it is built: the Morton keys and the sort's
// second array). Built on the preparation's threads, the same
// hierarchy on any number of them.
#pragma once
#include <cstddef>
#include <cstdint>

#include "memory/arrays.h"
#include "scene/scene.h"

namespace raycast {

// A node's eight children: their boxes as rows of eight floats (lo x, lo y,
// lo z, hi x, hi y, hi z; an empty slot's lo +inf and hi -inf, which no
// ray's slab test passes) and what each is (bvh_ref).
struct alignas(32) bvh_node {
  float box[6][8];
  uint32_t child[8];
};

// A child: an inner node's index, or a leaf (bit 31): its first sphere's
// position (bits 4 to 30) and its count less one (bits 0 to 3).
namespace bvh_ref {
inline constexpr uint32_t leaf_bit = 0x80000000u, empty = 0xffffffffu;
inline constexpr uint32_t most_in_leaf = 8;
inline constexpr uint32_t leaf(uint32_t first, uint32_t count) { return leaf_bit | first << 4 | (count - 1); }
inline constexpr bool is_leaf(uint32_t ref) { return (ref & leaf_bit) != 0; }
inline constexpr uint32_t first(uint32_t ref) { return (ref >> 4) & 0x7ffffffu; }
inline constexpr uint32_t count(uint32_t ref) { return (ref & 15u) + 1; }
}  // namespace bvh_ref

// What the kernels (light/kernels.h) read: plain pointers, as they are
// compiled once an instruction set and instantiate nothing shared.
struct bvh_view {
  const bvh_node* nodes = nullptr;
  uint32_t root = bvh_ref::empty;      // empty: no sphere
  // A leaf's n spheres as four rows of n (x, y, z, r), at 4 x its first
  // position: a leaf reads 16 n bytes in a row; 8 floats past the last.
  const float* leaf = nullptr;
  float max_r = 0;                     // the largest radius
};

// A sphere's centre (light frame) and radius (grid units): x y z r.
struct sphere4 {
  float v[4];
  float operator[](int a) const { return v[a]; }
};

class sphere_bvh {
 public:
  sphere_bvh() = default;
  // Without `open_nodes`, an open scene's (free_path() > open_free_path)
  // spheres and their leaves alone (runs of eight by position), for
  // light-space bins (light/far/shadow_bins.h), and its far field empty.
  sphere_bvh(const scene& s, int threads = 1, bool open_nodes = true);
  bool has_nodes() const { return root_ != bvh_ref::empty; }

  size_t size() const { return rank_.size(); }
  // Sphere k's (its index in the scene) position in the Morton order, and
  // the sphere at position p, read from its leaf's rows.
  uint32_t position(uint32_t k) const { return rank_[k]; }
  sphere4 at(uint32_t p) const {
    const uint32_t first = p - (place_[p] & 7u), n = (place_[p] >> 3) + 1u;
    const float* row = &leaf_[size_t(first) * 4 + (p - first)];
    return {{row[0], row[n], row[2 * n], row[3 * n]}};
  }
  sphere4 sphere(uint32_t k) const { return at(position(k)); }
  bvh_view view() const;

  double origin[3] = {0, 0, 0};
  int scale_exp = 0;  // grid units = world units * 2^-scale_exp
  float max_radius() const { return max_radius_; }
  // The median radius of up to 4096 spheres spread over the scene.
  double typical_radius() const { return typical_radius_; }
  // Spheres a unit volume (grid units) where they are: the count over the
  // leaves' boxes' summed volume (a cloud's frustum, not its bounding box).
  double density() const { return density_; }
  // A ray's mean free path among the spheres, in mean spacings: the
  // spheres' box's volume over their summed cross-section pi r^2, over the
  // cube root of the volume a sphere. About 1.8 in a box packed at 0.3, 16
  // and more in the bench's clouds. Above open_free_path a sphere's shadow
  // list would run through much of the scene: shadow rays ask light-space
  // bins instead.
  double free_path() const { return free_path_; }
  static constexpr double open_free_path = 3;

  size_t nodes() const { return nodes_.size(); }
  size_t leaves() const { return leaves_; }
  size_t bytes() const { return leaf_.size() * 4 + rank_.size() * 4 + place_.size() + nodes_.size() * sizeof(bvh_node); }

 private:
  sphere4 in_frame(const raycast::sphere& sp) const;
  void frame(const scene& s, int threads);
  void survey(const scene& s, int threads);
  void sort_by_morton(const scene& s, int threads, bool nodes);
  void build_nodes(const out_of_order_array<uint64_t>& keys, const out_of_order_array<float>& sorted, int threads);
  void fill_leaves(out_of_order_array<float>& sorted, int threads);

  out_of_order_array<float> leaf_;  // bvh_view::leaf
  // By position: the sphere's place in its leaf (bits 0 to 2) and its
  // leaf's count less one (bits 3 to 5).
  out_of_order_array<uint8_t> place_;
  out_of_order_array<uint32_t> rank_;
  out_of_order_array<bvh_node> nodes_;
  uint32_t root_ = bvh_ref::empty;
  size_t leaves_ = 0;
  float max_radius_ = 0;
  double unit_ = 1, volume_ = 0;       // 2^-scale_exp; the spheres' box's volume, grid units
  float centre_lo_[3] = {}, centre_hi_[3] = {};  // the centres' box, grid units
  double typical_radius_ = 0, density_ = 0, free_path_ = 0;
};

}  // namespace raycast
