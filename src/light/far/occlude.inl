// The far field's occlusion query (light/far/bvh.h), one ray at a time:
// each node's eight boxes in one vector step (a slab test from the ray's
// sign-chosen near and far planes), the children it meets visited front to
// back by octant (slot o ^ the ray's sign bits: a node's slots are its
// octants): its leaves' spheres tested there and then, a leaf a vector step,
// its nearest inner child next and the rest on a stack; done at the first
// sphere that blocks. Included by
// light/kernels_impl.cpp inside its width's namespace.
//
// The box test's rounding cannot lose a sphere: in grid units the planes
// and the start lie within [-1, 1], so a plane's t is off by a few float
// ulps of 2 / |d_a|, and the ray at it off the plane by some 1e-6, a tenth
// of the boxes' widening (far/nodes.h). A direction component below 2^-66
// is tested as that: over the segment the ray moves by less than 2^-60 on
// that axis (and its 1 / d stays finite, so an empty slot's infinite planes
// give no NaN).

// For sign bits s and a mask m of slots, the mask whose bit o is slot o ^ s's.
struct xor_orders {
  uint8_t of[8][256];
  constexpr xor_orders() : of{} {
    for (int s = 0; s < 8; ++s)
      for (int m = 0; m < 256; ++m)
        for (int o = 0; o < 8; ++o) of[s][m] = uint8_t(of[s][m] | ((m >> (o ^ s)) & 1) << o);
  }
};
constexpr xor_orders visit_order{};

// A ray's constants for the box tests.
struct far_ray {
  float o[3], inv[3];
  int near_row[3], far_row[3];
  uint32_t sign = 0;
  f8 d[3];

  far_ray() = default;
  RAYCAST_INLINE far_ray(const float org[3], const float dir[3]) {
    for (int a = 0; a < 3; ++a) {
      float da = dir[a];
      if (__builtin_fabsf(da) < 0x1p-66f) da = __builtin_copysignf(0x1p-66f, da);
      o[a] = org[a];
      inv[a] = 1.0f / da;
      const bool back = da < 0.0f;
      near_row[a] = back ? a + 3 : a;
      far_row[a] = back ? a : a + 3;
      sign |= uint32_t(back) << a;
      d[a] = dir[a] - f8{};
    }
  }
  // The slots of node n whose boxes the segment [t0, t1] passes through.
  RAYCAST_INLINE uint32_t meets(const bvh_node& n, float t0, float t1) const {
    const f8 nx = (load8(n.box[near_row[0]]) - o[0]) * inv[0], fx = (load8(n.box[far_row[0]]) - o[0]) * inv[0];
    const f8 ny = (load8(n.box[near_row[1]]) - o[1]) * inv[1], fy = (load8(n.box[far_row[1]]) - o[1]) * inv[1];
    const f8 nz = (load8(n.box[near_row[2]]) - o[2]) * inv[2], fz = (load8(n.box[far_row[2]]) - o[2]) * inv[2];
    const f8 enter = max(max(nx, ny), max(nz, t0 - f8{})), leave = min(min(fx, fy), min(fz, t1 - f8{}));
    return bits_of(le(enter, leave));
  }
};

// Leaf ref's spheres, a lane each (lanes past its count hold what follows).
RAYCAST_INLINE void leaf_spheres(const bvh_view& v, uint32_t ref, f8 s[4]) {
  const uint32_t n = bvh_ref::count(ref);
  const float* b = v.leaf + size_t(bvh_ref::first(ref)) * 4;
  s[0] = load8(b), s[1] = load8(b + n), s[2] = load8(b + 2 * n), s[3] = load8(b + 3 * n);
}

// Whether a sphere of leaf `ref` but skip meets the segment [t0, tmax].
RAYCAST_INLINE bool leaf_blocks(const bvh_view& v, uint32_t ref, const far_ray& ray, float t0, float tmax,
                                uint32_t skip) {
  const uint32_t first = bvh_ref::first(ref), n = bvh_ref::count(ref);
  f8 s[4];
  leaf_spheres(v, ref, s);
  uint32_t hit = bits_of(blocks_beyond<f8, i8>(ray.o, ray.d, s, t0, tmax)) & ((1u << n) - 1);
  if (skip - first < n) hit &= ~(1u << (skip - first));
  return hit != 0;
}

// The children of node n the segment meets, `order` its slots' bits in
// visiting order (o ^ sign the slot): the leaves tested here, the first inner
// node returned in next (or empty) and the rest pushed, last first. Whether
// a leaf blocked the segment.
RAYCAST_INLINE bool visit(const bvh_view& v, const bvh_node& n, uint32_t order, const far_ray& ray, float t0,
                          float tmax, uint32_t skip, uint32_t* stack, int& sp, uint32_t& next) {
  next = bvh_ref::empty;
  uint32_t inner = 0;
  for (uint32_t b = order; b != 0; b &= b - 1) {
    const uint32_t o = uint32_t(__builtin_ctz(b)), child = n.child[o ^ ray.sign];
    if (!bvh_ref::is_leaf(child)) inner |= 1u << o;
    else if (leaf_blocks(v, child, ray, t0, tmax, skip)) return true;
  }
  if (inner == 0) return false;
  next = n.child[__builtin_ctz(inner) ^ ray.sign];
  for (inner &= inner - 1; inner != 0;) {
    const uint32_t o = 31u - uint32_t(__builtin_clz(inner));
    stack[sp++] = n.child[o ^ ray.sign];
    inner ^= 1u << o;
  }
  return false;
}

// Whether a sphere of the subtree ref (a node or a leaf) blocks the ray.
bool far_walk(const bvh_view& v, uint32_t ref, const far_ray& ray, float t0, float tmax, uint32_t skip) {
  if (bvh_ref::is_leaf(ref)) return leaf_blocks(v, ref, ray, t0, tmax, skip);
  uint32_t stack[256];
  int sp = 0;
  for (;;) {
    const bvh_node& n = v.nodes[ref];
    const uint32_t hit = ray.meets(n, t0, tmax);
    if (hit != 0 && visit(v, n, visit_order.of[ray.sign][hit], ray, t0, tmax, skip, stack, sp, ref)) return true;
    if (hit != 0 && ref != bvh_ref::empty) continue;
    if (sp == 0) return false;
    ref = stack[--sp];
  }
}

bool far_occluded(const bvh_view& v, const float o[3], const float d[3], float t0, float tmax, uint32_t skip) {
  if (v.root == bvh_ref::empty || !(t0 <= tmax)) return false;
  return far_walk(v, v.root, far_ray(o, d), t0, tmax, skip);
}
