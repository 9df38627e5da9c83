// The far field's range queries, which the near field gathers its lists
// with (light/near/near_field.h): every sphere whose ball a region reaches,
// the nodes whose boxes it reaches visited (eight boxes a vector step), each
// leaf's spheres tested in one step. Included by light/kernels_impl.cpp
// inside its width's namespace.

// Appends the spheres of the leaf at `first` (its count n) set in `keep`,
// but self, to the rows (x, y, z, r, each with 8 floats of room past cap);
// returns the new count (cap + 1 once past cap). along: each one's value of
// `a` too, where not null.
RAYCAST_INLINE uint32_t add_kept(const f8 s[4], uint32_t first, uint32_t n, uint32_t keep, uint32_t self,
                                 float* const rows[4], uint32_t k, uint32_t cap, const f8* a = nullptr,
                                 float* along = nullptr) {
  keep &= (1u << n) - 1;
  if (self - first < 8) keep &= ~(1u << (self - first));
  const uint32_t count = uint32_t(__builtin_popcount(keep));
  if (k + count > cap) return cap + 1;
#if RAYCAST_LANES_WIDTH == 16
  // Compressed in a register and stored whole (a compressing store to
  // memory is microcoded on some CPUs).
  for (int c = 0; c < 4; ++c) _mm256_storeu_ps(rows[c] + k, _mm256_maskz_compress_ps(__mmask8(keep), __m256(s[c])));
  if (along) _mm256_storeu_ps(along + k, _mm256_maskz_compress_ps(__mmask8(keep), __m256(*a)));
#else
  for (uint32_t b = keep, at = k; b != 0; b &= b - 1, ++at) {
    const int l = __builtin_ctz(b);
    for (int c = 0; c < 4; ++c) rows[c][at] = s[c][l];
    if (along) along[at] = (*a)[l];
  }
#endif
  return k + count;
}

// The spheres j (but self) whose centres lie within reach + r_j of c: each
// box whose distance from c is at most reach (its spheres' balls lie in it).
uint32_t gather_ball(const bvh_view& v, const float c[3], float reach, uint32_t self, float* const rows[4],
                     uint32_t cap) {
  if (v.root == bvh_ref::empty) return 0;
  uint32_t stack[256], n = 0;
  int sp = 0;
  const float reach2 = reach * reach;
  for (uint32_t ref = v.root;;) {
    if (bvh_ref::is_leaf(ref)) {
      const uint32_t first = bvh_ref::first(ref);
      f8 s[4];
      leaf_spheres(v, ref, s);
      const f8 dx = s[0] - c[0], dy = s[1] - c[1], dz = s[2] - c[2], lim = reach + s[3];
      const uint32_t keep = bits_of(le((dx * dx + dy * dy) + dz * dz, lim * lim));
      n = add_kept(s, first, bvh_ref::count(ref), keep, self, rows, n, cap);
      if (n > cap) return n;
    } else {
      const bvh_node& node = v.nodes[ref];
      f8 d2 = {};
      for (int a = 0; a < 3; ++a) {
        const f8 gap = max(max(load8(node.box[a]) - c[a], c[a] - load8(node.box[a + 3])), f8{});
        d2 += gap * gap;
      }
      for (uint32_t hit = bits_of(le(d2, reach2)); hit != 0; hit &= hit - 1)
        stack[sp++] = node.child[__builtin_ctz(hit)];
    }
    if (sp == 0) return n;
    ref = stack[--sp];
  }
}

// The spheres j (but self) whose centres lie within r + r_j + slack of the
// line c + t l and at t >= -(r_j + slack), and each one's t: every box the
// ray from c - (largest r_j + slack) l meets once widened by r + slack on
// each side.
uint32_t gather_capsule(const bvh_view& v, const float c[3], float r, const float l[3], float slack, uint32_t self,
                        float* const rows[4], float* along, uint32_t cap) {
  if (v.root == bvh_ref::empty) return 0;
  const far_ray ray(c, l);
  const float widen = r + slack, behind = -(v.max_r + slack);
  uint32_t stack[256], n = 0;
  int sp = 0;
  for (uint32_t ref = v.root;;) {
    if (bvh_ref::is_leaf(ref)) {
      const uint32_t first = bvh_ref::first(ref);
      f8 s[4];
      leaf_spheres(v, ref, s);
      const f8 wx = s[0] - c[0], wy = s[1] - c[1], wz = s[2] - c[2];
      const f8 a = (wx * l[0] + wy * l[1]) + wz * l[2];
      const f8 px = wx - a * l[0], py = wy - a * l[1], pz = wz - a * l[2];
      const f8 lim = (r + s[3]) + slack;
      const i8 keep = le((px * px + py * py) + pz * pz, lim * lim) & le(-(s[3] + slack), a);
      n = add_kept(s, first, bvh_ref::count(ref), bits_of(keep), self, rows, n, cap, &a, along);
      if (n > cap) return n;
    } else {
      const bvh_node& node = v.nodes[ref];
      f8 lo[3], hi[3];
      for (int a = 0; a < 3; ++a) lo[a] = load8(node.box[a]) - widen, hi[a] = load8(node.box[a + 3]) + widen;
      const f8 nx = ((ray.sign & 1 ? hi[0] : lo[0]) - c[0]) * ray.inv[0], fx = ((ray.sign & 1 ? lo[0] : hi[0]) - c[0]) * ray.inv[0];
      const f8 ny = ((ray.sign & 2 ? hi[1] : lo[1]) - c[1]) * ray.inv[1], fy = ((ray.sign & 2 ? lo[1] : hi[1]) - c[1]) * ray.inv[1];
      const f8 nz = ((ray.sign & 4 ? hi[2] : lo[2]) - c[2]) * ray.inv[2], fz = ((ray.sign & 4 ? lo[2] : hi[2]) - c[2]) * ray.inv[2];
      const f8 enter = max(max(nx, ny), max(nz, behind - f8{})), leave = min(min(fx, fy), fz);
      for (uint32_t b = bits_of(le(enter, leave)); b != 0; b &= b - 1) stack[sp++] = node.child[__builtin_ctz(b)];
    }
    if (sp == 0) return n;
    ref = stack[--sp];
  }
}
