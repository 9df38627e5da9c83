// The far field's occlusion query for up to eight rays from one origin (a
// hit's AO rays past its near list), walked together: an entry of the
// walk's stack is a node and the rays that met its box. Each node's boxes
// are tested once a ray of the entry, the eight verdicts transposed into the
// rays that meet each child (byte c of the result: child c's rays), and the
// met children pushed with their rays, nearest last by the first ray's
// octant order; a leaf's spheres are read once for all its rays; a blocked
// ray leaves every entry. An entry left with one ray walks on alone
// (far_walk, far/occlude.inl), since the rays of a hit part after a few
// nodes and a ray's own walk is the cheaper there. Each ray's verdict is
// far_occluded's: any order of the same tests. Included by
// light/kernels_impl.cpp inside its width's namespace, after occlude.inl.

// Bit c of byte r to bit r of byte c: an 8 x 8 bit matrix transposed in
// three swaps of its 4 x 4, 2 x 2 and 1 x 1 blocks.
RAYCAST_INLINE uint64_t transpose8(uint64_t x) {
  uint64_t t = (x ^ (x >> 7)) & 0x00aa00aa00aa00aaull;
  x = x ^ t ^ (t << 7);
  t = (x ^ (x >> 14)) & 0x0000cccc0000ccccull;
  x = x ^ t ^ (t << 14);
  t = (x ^ (x >> 28)) & 0x00000000f0f0f0f0ull;
  return x ^ t ^ (t << 28);
}

// Which of leaf ref's spheres but skip block each of `rays` (its bit r: ray
// r): the rays that one does.
RAYCAST_INLINE uint32_t leaf_blocks_rays(const bvh_view& v, uint32_t ref, const far_ray* ray, uint32_t rays,
                                         float t0, float tmax, uint32_t skip) {
  const uint32_t first = bvh_ref::first(ref), n = bvh_ref::count(ref);
  uint32_t spheres = (1u << n) - 1;
  if (skip - first < n) spheres &= ~(1u << (skip - first));
  f8 s[4];
  leaf_spheres(v, ref, s);
  uint32_t blocked = 0;
  for (uint32_t b = rays; b != 0; b &= b - 1) {
    const int r = __builtin_ctz(b);
    if (bits_of(blocks_beyond<f8, i8>(ray[r].o, ray[r].d, s, t0, tmax)) & spheres) blocked |= 1u << r;
  }
  return blocked;
}

uint32_t far_occluded_one_origin(const bvh_view& v, const float o[3], const float (*d)[3], uint32_t m, float t0,
                                 float tmax, uint32_t skip) {
  if (v.root == bvh_ref::empty || !(t0 <= tmax) || m == 0) return 0;
  far_ray ray[8];
  for (uint32_t r = 0; r < m; ++r) ray[r] = far_ray(o, d[r]);
  struct entry {
    uint32_t ref, rays;
  } stack[8 * 64];
  int sp = 0;
  uint32_t open = (1u << m) - 1, blocked = 0;
  stack[sp++] = {v.root, open};
  while (sp > 0 && open != 0) {
    const entry e = stack[--sp];
    const uint32_t rays = e.rays & open;
    if (rays == 0) continue;
    uint32_t now = 0;
    if ((rays & (rays - 1)) == 0) {
      const int r = __builtin_ctz(rays);
      now = far_walk(v, e.ref, ray[r], t0, tmax, skip) ? rays : 0;
    } else if (bvh_ref::is_leaf(e.ref)) {
      now = leaf_blocks_rays(v, e.ref, ray, rays, t0, tmax, skip);
    } else {
      const bvh_node& n = v.nodes[e.ref];
      uint64_t met = 0;  // byte r: the slots ray r meets
      for (uint32_t b = rays; b != 0; b &= b - 1) {
        const int r = __builtin_ctz(b);
        met |= uint64_t(ray[r].meets(n, t0, tmax)) << (8 * r);
      }
      const uint64_t by_child = transpose8(met);
      const uint32_t sign = ray[__builtin_ctz(rays)].sign;
      for (int k = 7; k >= 0; --k) {  // the nearest pushed last
        const uint32_t slot = uint32_t(k) ^ sign, with = uint32_t(by_child >> (8 * slot)) & 0xffu;
        stack[sp] = {n.child[slot], with};
        sp += with != 0;
      }
    }
    blocked |= now;
    open &= ~now;
  }
  return blocked;
}
