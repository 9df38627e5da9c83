// Rays against a near-field list (light/near/near_field.h), sixteen of its
// spheres a vector step, done at the first that blocks. Included by
// light/kernels_impl.cpp inside its width's namespace.

bool list_blocks(const sphere_blocks& list, const float o[3], const float d[3], float tmax) {
  const f16 dir[3] = {d[0] - f16{}, d[1] - f16{}, d[2] - f16{}};
  for (uint32_t i = 0; i < list.count; i += 16) {
    const float* p = list.blocks + size_t(i) * 4;
    const f16 s[4] = {load16(p), load16(p + 16), load16(p + 32), load16(p + 48)};
    if (bits_of(blocks<f16, i16>(o, dir, s, tmax)) != 0) return true;
  }
  return false;
}

// A hit's cut list, the spheres as seen from its origin o: rows w = o - C_j
// (x, y, z) and c = |w|^2 - r_j^2, each padded with NaN to a multiple of
// 16; any c <= 0 (o inside a ball) blocks every ray.
constexpr uint32_t cut_most = 1024;  // near_field::most_listed
struct cut_list {
  alignas(64) float row[4][cut_most + 16];
  uint32_t count = 0;
  bool inside = false;
};

// The list's spheres that can meet a ray from o into the hemisphere about n
// within `within`: those whose balls reach above o's tangent plane (less a
// 2^-12 of the distance, far more than a ray's dip below it by rounding)
// within within + r_j of o.
RAYCAST_INLINE void cut_to_hemisphere(const sphere_blocks& list, const float o[3], const float n[3], float within,
                                      cut_list& cut) {
  uint32_t k = 0;
  i16 inside = {};
  for (uint32_t i = 0; i < list.count; i += 16) {
    const float* p = list.blocks + size_t(i) * 4;
    const f16 r = load16(p + 48);
    const f16 w[4] = {o[0] - load16(p), o[1] - load16(p + 16), o[2] - load16(p + 32), {}};
    const f16 w2 = (w[0] * w[0] + w[1] * w[1]) + w[2] * w[2], lim = within + r;
    const f16 down = (w[0] * n[0] + w[1] * n[1]) + w[2] * n[2];  // how far o lies above C_j along n
    const f16 c = w2 - r * r;
    inside |= le(c, 0.0f);
    const uint32_t bits = bits_of(le(w2, lim * lim) & le(down, r + lim * 0x1p-12f));
    const f16 row[4] = {w[0], w[1], w[2], c};
#if RAYCAST_LANES_WIDTH == 16
    // Compressed in a register and stored whole (a compressing store to
    // memory is microcoded on some CPUs); the row has 16 floats of room.
    for (int a = 0; a < 4; ++a) _mm512_storeu_ps(cut.row[a] + k, _mm512_maskz_compress_ps(__mmask16(bits), __m512(row[a])));
    k += uint32_t(__builtin_popcount(bits));
#else
    for (uint32_t b = bits; b != 0; b &= b - 1, ++k)
      for (int a = 0; a < 4; ++a) cut.row[a][k] = row[a][__builtin_ctz(b)];
#endif
  }
  for (uint32_t e = k; e % 16 != 0; ++e)
    for (int a = 0; a < 4; ++a) cut.row[a][e] = __builtin_nanf("");
  cut.count = k;
  cut.inside = bits_of(inside) != 0;
}

// Whether the ray along d (of unit length) meets a ball of the cut within
// tmax: b = w . d, the ball ahead (b < 0) and the line within it (its gap
// b^2 - c >= 0), its near root -b - sqrt(gap) within tmax (compared squared).
// From a hit's origin a list's spheres lie within a few radii, so b^2 - c
// loses no more than Hearn and Baker's form would (lanes::blocks).
RAYCAST_INLINE bool cut_blocks(const cut_list& cut, const float d[3], float tmax) {
  for (uint32_t i = 0; i < cut.count; i += 16) {
    const f16 b = (load16(cut.row[0] + i) * d[0] + load16(cut.row[1] + i) * d[1]) + load16(cut.row[2] + i) * d[2];
    const f16 gap = b * b - load16(cut.row[3] + i), beyond = -b - tmax;
    const i16 hit = lt(b, 0.0f) & ge(gap, 0.0f) & (le(beyond, 0.0f) | le(beyond * beyond, gap));
    if (bits_of(hit) != 0) return true;
  }
  return false;
}

uint32_t list_ao(const sphere_blocks& list, const float o[3], const float n[3], const float (*d)[3], int m, float tmax,
                 float within) {
  cut_list cut;
  cut_to_hemisphere(list, o, n, within, cut);
  const uint32_t all = (1u << m) - 1;
  if (cut.inside) return all;
  uint32_t hit = 0;
  for (int ray = 0; ray < m; ++ray) hit |= uint32_t(cut_blocks(cut, d[ray], tmax)) << ray;
  return hit;
}
