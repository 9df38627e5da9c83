// The sky kernel, compiled per target: batches of a row quantized and interleaved in registers.
#include <type_traits>

#include "kernels/sky_shade.inl"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

// Fast mode's Newton step's constants, biased up by 2^-20 (kernels/scalar.h).
constexpr float fast_nr_a = 1.5f * (1.0f + 0x1p-20f);
constexpr float fast_nr_b = 0.5f * (1.0f + 0x1p-20f);

// Per row: sv * vertical[k], and for the axis-aligned camera the row's d.y and squares; fast mode
// adds y2 + z2 first (it need not keep exact mode's order) and folds d.y into the Newton constants.
struct row_setup {
  float row_part[3];
  float dy, y2, z2;
  float yz2, nr_a, nr_b;
};

// A batch's rays: the sky reads only d.y and |d|^2.
struct ray_batch {
  vfloat dir_y;  // d.y
  vfloat len2;   // |d|^2 = (d.x^2 + d.y^2) + d.z^2, in scalar.h's order for exact mode
};

template <bool Lanes, bool Fast>
inline ray_batch generate(const kernel_args& a, const row_setup& rs, int64_t i0) {
  if constexpr (Lanes) {
    const vfloat x2 = vfloat::load(a.column_x2 + i0);
    if constexpr (Fast) return {rs.dy, x2 + rs.yz2};
    return {rs.dy, (x2 + rs.y2) + rs.z2};
  } else {
    const vfloat dx = vfloat::load(a.column_part[0] + i0) + rs.row_part[0];
    const vfloat dy = vfloat::load(a.column_part[1] + i0) + rs.row_part[1];
    const vfloat dz = vfloat::load(a.column_part[2] + i0) + rs.row_part[2];
    return {dy, (dx * dx + dy * dy) + dz * dz};
  }
}

// Fast mode: y / |d| from the estimate and one biased Newton step, clamped to [-1, 1] (scalar.h).
template <bool Lanes>
inline vfloat fast_uy(const row_setup& rs, const ray_batch& b) {
  const vfloat n2 = max(b.len2, FLT_MIN);
  const vfloat r = rsqrt_est(n2);
  const vfloat e = (n2 * r) * r;
  vfloat uy;
  if constexpr (Lanes) uy = r * nmadd(e, rs.nr_b, rs.nr_a);
  else uy = (b.dir_y * r) * nmadd(e, fast_nr_b, fast_nr_a);
  return clamp(uy, -1.0f, 1.0f);
}

// Channel sets the kernel has loops for (bit k: channel k is computed; else a constant).
constexpr int all_channels = 0b111;
constexpr int red_green = 0b011;  // the lesson's sky: blue is 1 at both ends

template <bool NoClamps, int Computed>
struct shader {
  sky_colors sky;
  vfloat constant_value[3];
  vint constant_byte[3];
  vfloat fast_qa[3], fast_qb[3];

  explicit shader(const kernel_args& a) : sky(*a.scene) {
    const float_scene& s = *a.scene;
    for (int k = 0; k < 3; ++k) {
      constant_value[k] = a.constant_value[k];
      constant_byte[k] = splat_int(a.constant_byte[k]);
      fast_qa[k] = s.fast_qa[k];
      fast_qb[k] = s.fast_qb[k];
    }
  }

  template <int K>
  vfloat channel(vfloat t) const {
    if constexpr (!(Computed & (1 << K))) return constant_value[K];
    return sky.channel<NoClamps>(K, t);
  }
  template <int K>
  vint byte(vfloat c) const {
    if constexpr (!(Computed & (1 << K))) return constant_byte[K];
    return to_int((NoClamps ? c : clamp(c, 0.0f, 1.0f)) * 255.999f);
  }
  // Fast mode, 8-bit: one multiply-add on uy; with colours in [0, 1] the result is in [0, 256).
  template <int K>
  vint fast_byte(vfloat uy) const {
    if constexpr (!(Computed & (1 << K))) return constant_byte[K];
    const vfloat x = madd(uy, fast_qa[K], fast_qb[K]);
    return to_int(NoClamps ? x : clamp(x, 0.0f, 255.999f));
  }
};

// 8-bit: one batch shaded from its uy and interleaved; Reversed, in the opposite order.
template <bool Fast, bool Reversed, bool NoClamps, int Computed>
inline rgb8_pack shade_rgb8(const shader<NoClamps, Computed>& sh, vfloat uy) {
  if constexpr (Fast) {
    return pack_rgb8<Reversed>(sh.template fast_byte<0>(uy), sh.template fast_byte<1>(uy),
                               sh.template fast_byte<2>(uy));
  } else {
    const vfloat t = sky_t(uy);
    return pack_rgb8<Reversed>(sh.template byte<0>(sh.template channel<0>(t)),
                               sh.template byte<1>(sh.template channel<1>(t)),
                               sh.template byte<2>(sh.template channel<2>(t)));
  }
}

// Float: one batch shaded and n pixels stored at column i0; mirrored, lane L at i0 + N - 1 - L.
template <bool NoClamps, int Computed>
inline void shade_store_f32(const shader<NoClamps, Computed>& sh, vfloat uy, unsigned char* out,
                            int64_t i0, int n, bool mirrored) {
  const vfloat t = sky_t(uy);
  vfloat c0 = sh.template channel<0>(t), c1 = sh.template channel<1>(t), c2 = sh.template channel<2>(t);
  if (mirrored) {
    if constexpr ((Computed & 1) != 0) c0 = reverse(c0);
    if constexpr ((Computed & 2) != 0) c1 = reverse(c1);
    if constexpr ((Computed & 4) != 0) c2 = reverse(c2);
  }
  float* dst = reinterpret_cast<float*>(out) + 3 * i0;
  if (n == N) {
    store_rgbf(dst, c0, c1, c2);
  } else {
    alignas(64) float tmp[3 * N];
    store_rgbf(tmp, c0, c1, c2);
    __builtin_memcpy(dst, tmp, sizeof(float) * 3 * size_t(n));
  }
}

template <bool Fast, bool NoClamps, int Computed>
inline void shade_store_rgb8(const shader<NoClamps, Computed>& sh, vfloat uy, unsigned char* out,
                             int64_t i0, int n, bool mirrored) {
  unsigned char* dst = out + 3 * i0;
  if (mirrored) {
    store(dst, shade_rgb8<Fast, true>(sh, uy));
  } else if (n == N) {
    store(dst, shade_rgb8<Fast, false>(sh, uy));
  } else {
#ifdef RAYCAST_HAS_MASKED_BYTE_STORE
    store_first(dst, shade_rgb8<Fast, false>(sh, uy), n);
#else
    alignas(64) unsigned char tmp[3 * N];
    store(tmp, shade_rgb8<Fast, false>(sh, uy));
    __builtin_memcpy(dst, tmp, 3 * size_t(n));
#endif
  }
}

// Four packs side by side: whole cache-line writes where the target has them (store4).
inline void store_four(unsigned char* dst, rgb8_pack a, rgb8_pack b, rgb8_pack c, rgb8_pack d) {
#ifdef RAYCAST_HAS_STORE4
  store4(dst, a, b, c, d);
#else
  store(dst, a);
  store(dst + 3 * N, b);
  store(dst + 6 * N, c);
  store(dst + 9 * N, d);
#endif
}

// Rows [r0, r1); with `paired`, each row r together with its mirror H-1-r. The lesson camera's
// column W-1-i has column i's |d| and y, row H-1-r the same |d| and -y: a batch's |d| serves up to
// four batches; only a row's middle, under two batches wide, is unmirrored. 8-bit rows go four
// batches at a time where they can (store4).
template <bool Lanes, bool Fast, bool Float, bool NoClamps, int Computed>
void render(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1, bool paired) {
  const float_scene& s = *a.scene;
  const shader<NoClamps, Computed> sh(a);
  const int64_t W = s.width, c0 = band.col_begin, c1 = band.cols_end(W);
  const bool whole_rows = band.whole_rows(W);
  const int64_t mirrored = Lanes && a.mirror && whole_rows ? W / (2 * N) * N : 0;
  for (int64_t r = r0; r < r1; ++r) {
    const int64_t j = s.height - 1 - r;
    const float sv = pixel_sv(s, j);
    row_setup rs;
    for (int k = 0; k < 3; ++k) rs.row_part[k] = sv * s.vertical[k];
    // Lesson camera: scalar.h's d.y = (0 + su*0) + sv*vy and d.z = (-f + su*0) + sv*0 are sv*vy
    // and -f up to the sign of a zero, which no square sees.
    rs.dy = (s.center[1] + 0.0f) + rs.row_part[1];
    rs.y2 = rs.dy * rs.dy;
    rs.z2 = s.center[2] * s.center[2];
    rs.yz2 = rs.y2 + rs.z2;
    rs.nr_a = fast_nr_a * rs.dy;
    rs.nr_b = fast_nr_b * rs.dy;
    unsigned char* const rows[2] = {
        band.row(r), paired && s.height - 1 - r != r ? band.row(s.height - 1 - r) : nullptr};
    const auto uy_at = [&](int64_t i0) {
      const ray_batch rays = generate<Lanes, Fast>(a, rs, i0);
      return Fast ? fast_uy<Lanes>(rs, rays) : exact_uy(rays.dir_y, rays.len2);
    };
    const auto row_uy = [](vfloat uy, int k) { return k == 0 ? uy : -uy; };

    if (!whole_rows) {  // a region (image_band's column window): batches on the row's grid
      constexpr size_t bpp = Float ? 12 : 3;
      for (int64_t i0 = c0 / N * N; i0 < c1; i0 += N) {
        const vfloat uy = uy_at(i0);
        const int64_t lo = i0 > c0 ? i0 : c0, hi = i0 + N < c1 ? i0 + N : c1;
        const bool whole = lo == i0 && hi == i0 + N;
        alignas(64) unsigned char tmp[bpp * N];
        unsigned char* const dst = whole ? rows[0] + bpp * size_t(i0 - c0) : tmp;
        if constexpr (Float) shade_store_f32(sh, uy, dst, 0, N, false);
        else shade_store_rgb8<Fast>(sh, uy, dst, 0, N, false);
        if (!whole) __builtin_memcpy(rows[0] + bpp * size_t(lo - c0), tmp + bpp * size_t(lo - i0), bpp * size_t(hi - lo));
      }
      continue;
    }
    int64_t i0 = 0;
    if constexpr (!Float) {
      for (; i0 + 4 * N <= mirrored; i0 += 4 * N) {
        const vfloat uy[4] = {uy_at(i0), uy_at(i0 + N), uy_at(i0 + 2 * N), uy_at(i0 + 3 * N)};
        for (int k = 0; k < 2 && rows[k]; ++k) {
          rgb8_pack p[4], m[4];
          for (int b = 0; b < 4; ++b) {
            p[b] = shade_rgb8<Fast, false>(sh, row_uy(uy[b], k));
            m[b] = shade_rgb8<Fast, true>(sh, row_uy(uy[b], k));
          }
          store_four(rows[k] + 3 * i0, p[0], p[1], p[2], p[3]);
          store_four(rows[k] + 3 * (W - i0 - 4 * N), m[3], m[2], m[1], m[0]);
        }
      }
    }
    for (; i0 < W - mirrored; i0 += N) {
      const bool mirror = i0 < mirrored;
      const int n = mirror || W - mirrored - i0 >= N ? N : int(W - mirrored - i0);
      const vfloat uy = uy_at(i0);
      for (int k = 0; k < 2 && rows[k]; ++k) {
        const vfloat u = row_uy(uy, k);
        if constexpr (Float) {
          shade_store_f32(sh, u, rows[k], i0, n, false);
          if (mirror) shade_store_f32(sh, u, rows[k], W - i0 - N, N, true);
        } else {
          shade_store_rgb8<Fast>(sh, u, rows[k], i0, n, false);
          if (mirror) shade_store_rgb8<Fast>(sh, u, rows[k], W - i0 - N, N, true);
        }
      }
    }
  }
}

// Calls f with a compile-time copy of a run-time flag: each combination is its own loop.
template <class F>
inline void with_flag(bool flag, F&& f) {
  if (flag) f(std::true_type{});
  else f(std::false_type{});
}

}  // namespace

void render_sky_rows(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1, bool paired) {
  const bool fast = a.prec == precision::fast;
  const bool f32 = band.format == pixel_format::rgb_f32;
  const bool no_clamps = a.lerp_exact && (f32 || a.colors_in_unit_range);
  int computed = 0;
  for (int k = 0; k < 3; ++k) computed |= a.constant[k] ? 0 : 1 << k;
  paired = paired && a.lanes && a.mirror;
  // Other channel sets run the all-channels loop, exact for them too (bottom + t * 0 = bottom).
  with_flag(a.lanes, [&](auto lanes) {
    with_flag(fast, [&](auto fast_mode) {
      with_flag(f32, [&](auto float_out) {
        with_flag(no_clamps, [&](auto unclamped) {
          constexpr bool Lanes = decltype(lanes)::value, Fast = decltype(fast_mode)::value,
                         Float = decltype(float_out)::value, NoClamps = decltype(unclamped)::value;
          if (computed == red_green) render<Lanes, Fast, Float, NoClamps, red_green>(a, band, r0, r1, paired);
          else render<Lanes, Fast, Float, NoClamps, all_channels>(a, band, r0, r1, paired);
        });
      });
    });
  });
}

}  // namespace raycast::kernels::RAYCAST_ISA
