// The culling's geometry (culling.h): which rows and columns may see a sphere, in double.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "prepare/float_scene.h"

namespace raycast::culling_detail {

// Rays of a row: d(su) = a + su h, su in [-1/2, 1/2] (scalar.h, in double).
struct row_rays {
  double a[3], h[3];
};

inline double dot(const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }

inline void cross(const double* x, const double* y, double* out) {
  out[0] = x[1] * y[2] - x[2] * y[1];
  out[1] = x[2] * y[0] - x[0] * y[2];
  out[2] = x[0] * y[1] - x[1] * y[0];
}

// Where alpha x^2 + 2 beta x + gamma <= 0: empty, one bounded interval [s0, s1], or not one
// (alpha <= 0, or NaN: unbounded). Branch-free, so many spheres' roots overlap (boxes_of).
struct solved {
  enum : uint8_t { empty, bounded, unbounded };
  double s0, s1;
  uint8_t kind;
};
inline solved solve_below_zero(double alpha, double beta, double gamma) {
  const double disc = beta * beta - alpha * gamma;
  const double q = -(beta + std::copysign(std::sqrt(disc), beta));
  const double r0 = q / alpha, r1 = q != 0.0 ? gamma / q : r0;
  const bool open = !(alpha > 0.0) || std::isnan(disc);
  return {r0 > r1 ? r1 : r0, r0 > r1 ? r0 : r1,
          uint8_t(open ? solved::unbounded : disc < 0.0 ? solved::empty : solved::bounded)};
}

// solve_below_zero's interval into [s0, s1]: left as given where unbounded, false where empty.
inline bool below_zero(double alpha, double beta, double gamma, double& s0, double& s1) {
  const solved r = solve_below_zero(alpha, beta, gamma);
  if (r.kind == solved::bounded) s0 = r.s0, s1 = r.s1;
  return r.kind != solved::empty;
}

// The indices [i0, i1] (whole numbers in double) clamped to [0, count); false when none is inside.
inline bool clamp_indices(double i0, double i1, int64_t count, int64_t& lo, int64_t& hi) {
  if (i1 < 0.0 || i0 > double(count - 1) || i0 > i1) return false;
  lo = i0 > 0.0 ? int64_t(i0) : 0;  // (NaN: 0)
  hi = i1 < double(count - 1) ? int64_t(i1) : count - 1;
  return true;
}

// The indices i in [0, count) with (i - mid) / last in [s0, s1] (su or sv: kernels/scalar.h),
// widened by slack each way, as [lo, hi]; false when there is none.
inline bool index_range(double s0, double s1, float last, float mid, double slack, int64_t count, int64_t& lo,
                 int64_t& hi) {
  const double i0 = std::floor(s0 * double(last) + double(mid)) - slack;
  const double i1 = std::ceil(s1 * double(last) + double(mid)) + slack;
  return clamp_indices(i0, i1, count, lo, hi);
}

// The columns [lo, hi] of the row whose rays come within r of the centre (f = O - C, in the
// sphere's unit): their lines do where |f x d|^2 <= r^2 |d|^2, a quadratic in su; a camera
// `outside` the unwidened culling radius also needs the centre ahead, f.d <= m (linear in su; the
// slack m covers rays that stray). False when no column's does.
inline bool columns_near(const float_scene& fs, const row_rays& rr, const double* f, double r, bool outside, double m,
                  int64_t& lo, int64_t& hi) {
  double A[3], B[3];
  cross(f, rr.a, A);
  cross(f, rr.h, B);
  const double r2 = r * r;
  const double alpha = dot(B, B) - r2 * dot(rr.h, rr.h);
  const double beta = dot(A, B) - r2 * dot(rr.a, rr.h);
  const double gamma = dot(A, A) - r2 * dot(rr.a, rr.a);
  double s0 = -INFINITY, s1 = INFINITY;  // the su interval
  if (!below_zero(alpha, beta, gamma, s0, s1)) return false;  // no line comes near
  if (outside) {  // the centre must be ahead
    const double g0 = dot(f, rr.a), g1 = dot(f, rr.h);
    if (g1 > 0.0) s1 = std::min(s1, (m - g0) / g1);
    else if (g1 < 0.0) s0 = std::max(s0, (m - g0) / g1);
    else if (g0 > m) return false;
  }
  if (fs.width == 1) return !(s0 > 0.0 || s1 < 0.0);
  return index_range(s0, s1, fs.last_col, fs.mid_col, 1.0, fs.width, lo, hi);
}

// The culling radius for rays that may stray by spread (float_scene.h).
inline double widened(const float_spheres& sp, uint32_t k, double spread) {
  if (spread == 0.0) return sp.cull_radius[k];
  const double f2 = double(sp.rec[k].fx) * sp.rec[k].fx + double(sp.rec[k].fy) * sp.rec[k].fy + double(sp.rec[k].fz) * sp.rec[k].fz;
  return sp.cull_radius[k] + spread * std::sqrt(f2);
}

// Sphere k's centre and reach on an orthographic camera's plane in world units, widened by spread.
struct plane_disc {
  double cx, cy, w;
  bool behind;  // entirely behind the image plane: no ray meets it
};
inline plane_disc disc_of(const float_scene& f, uint32_t k, double spread) {
  const sphere_record& e = f.spheres.rec[k];
  const double scale = e.scale, w = (f.spheres.cull_radius[k] + spread / scale) * scale;
  return {double(e.fx) * scale, double(e.fy) * scale, w, double(e.fz) * scale + f.plane_offset + w < 0.0};
}

// The indices whose plane position ((i - mid) / last extent) is in [lo, hi], one slack each way.
inline bool plane_range(double lo, double hi, double extent, float last, float mid, int64_t count, int64_t& a, int64_t& b) {
  if (count == 1) {
    a = b = 0;
    return lo <= 0.0 && hi >= 0.0;
  }
  return index_range(lo / extent, hi / extent, last, mid, 1.0, count, a, b);
}

// A family of planes through the camera origin: plane s, s = (i - mid) / last, is spanned by
// a + s step and along (the rows': step = vertical, along = horizontal; the columns' the other
// way round), with normal N0 + s N1 (N0 = a x along, N1 = step x along).
struct plane_family {
  double N0[3], N1[3], n00, n01, n11;
  float last, mid;
  int64_t count;
  double n_max;  // the most |N0 + s N1| for s in [-1/2, 1/2] (at an end: |n|^2 is convex)

  plane_family(const double* a, const double* step, const double* along, float last_, float mid_, int64_t count_)
      : last(last_), mid(mid_), count(count_) {
    cross(a, along, N0);
    cross(step, along, N1);
    n00 = dot(N0, N0);
    n01 = dot(N0, N1);
    n11 = dot(N1, N1);
    n_max = std::sqrt(std::max(n00 - n01 + 0.25 * n11, n00 + n01 + 0.25 * n11));
  }

  // The indices whose plane comes within w of the sphere at fk: (fk.n)^2 <= w^2 |n|^2, a quadratic
  // in s, rounded outwards (near(), then indices()); false when none does.
  bool range(const double* fk, double w, int64_t& lo, int64_t& hi) const { return indices(near(fk, w), lo, hi); }
  solved near(const double* fk, double w) const {
    const double w2 = w * w, p0 = dot(fk, N0), p1 = dot(fk, N1);
    return solve_below_zero(p1 * p1 - w2 * n11, p0 * p1 - w2 * n01, p0 * p0 - w2 * n00);
  }
  bool indices(const solved& s, int64_t& lo, int64_t& hi) const {
    lo = 0;
    hi = count - 1;
    if (s.kind == solved::empty) return false;
    if (count == 1) return true;  // one index: the plane test decides
    return s.kind == solved::unbounded ? index_range(-INFINITY, INFINITY, last, mid, 0.0, count, lo, hi)
                                       : index_range(s.s0, s.s1, last, mid, 0.0, count, lo, hi);
  }
};

// The camera's vectors in double, and what every sphere's box needs of them.
struct frame_vectors {
  double c[3], h[3], v[3];
  double d_len;  // >= |d| for every ray of the frame
  plane_family rows, cols;

  explicit frame_vectors(const float_scene& f)
      : c{f.center[0], f.center[1], f.center[2]},
        h{f.horizontal[0], f.horizontal[1], f.horizontal[2]},
        v{f.vertical[0], f.vertical[1], f.vertical[2]},
        d_len(std::sqrt(dot(c, c)) + std::sqrt(dot(h, h)) + std::sqrt(dot(v, v))),
        rows(c, v, h, f.last_row, f.mid_row, f.height),
        cols(c, h, v, f.last_col, f.mid_col, f.width) {}
};

// The exact test of a sphere against a row's rays.
struct row_test {
  const float_scene& f;
  double spread;
  row_rays rr;
  double n[3], len = 0.0, d_len = 0.0;
  bool plane = false;
  float sv;

  row_test(const float_scene& fs, float sv_, double spread_) : f(fs), spread(spread_), sv(sv_) {
    // The row's plane through the origin, spanned by a = centre + sv vertical and horizontal.
    for (int k = 0; k < 3; ++k) {
      rr.a[k] = double(f.center[k]) + double(sv) * double(f.vertical[k]);
      rr.h[k] = double(f.horizontal[k]);
    }
    cross(rr.a, rr.h, n);
    len = std::sqrt(dot(n, n));
    plane = len > 0.0 && std::isfinite(len);  // else a degenerate row: no plane test
    d_len = std::sqrt(dot(rr.a, rr.a)) + std::sqrt(dot(rr.h, rr.h));  // >= |d| in the row
  }

  bool columns(uint32_t k, int64_t& lo, int64_t& hi) const {
    if (f.orthographic) {  // the row's line across the plane through the sphere's disc
      const plane_disc d = disc_of(f, k, spread);
      const double dy = double(sv) * f.plane_height - d.cy;
      if (d.behind || !(std::abs(dy) <= d.w)) return false;
      const double half = std::sqrt(d.w * d.w - dy * dy);
      return plane_range(d.cx - half, d.cx + half, f.plane_width, f.last_col, f.mid_col, f.width, lo, hi);
    }
    const float_spheres& sp = f.spheres;
    const double fk[3] = {sp.rec[k].fx, sp.rec[k].fy, sp.rec[k].fz};
    const double wide = widened(sp, k, spread);
    if (plane && std::abs(dot(fk, n)) > wide * len) return false;  // NaN: kept
    lo = 0;
    hi = f.width - 1;
    const double ahead_slack = (wide - std::sqrt(double(sp.rec[k].r2))) * d_len;
    const bool outside = dot(fk, fk) > sp.cull_radius[k] * sp.cull_radius[k];
    return columns_near(f, rr, fk, wide, outside, ahead_slack, lo, hi);
  }
};

// The index keeps a column box for spheres under this many rows tall; taller get row_test per row.
constexpr int64_t boxed_rows = 64;

// A sphere's rows and, if short, columns (no member initializers: arrays of them are not zeroed).
struct frame_box {
  int32_t r_lo, r_hi;  // rows, top-down (r = H - 1 - j); empty when r_lo > r_hi
  int32_t c_lo, c_hi;  // columns; -1: tested per row
};

inline frame_box box_of_ortho(const float_scene& f, uint32_t k, double spread) {
  frame_box box{1, 0, -1, -1};  // in no row
  const plane_disc d = disc_of(f, k, spread);
  int64_t j_lo = 0, j_hi = 0, c_lo = 0, c_hi = 0;
  if (d.behind || !plane_range(d.cy - d.w, d.cy + d.w, f.plane_height, f.last_row, f.mid_row, f.height, j_lo, j_hi) ||
      !plane_range(d.cx - d.w, d.cx + d.w, f.plane_width, f.last_col, f.mid_col, f.width, c_lo, c_hi))
    return box;
  box.r_lo = int32_t(f.height - 1 - j_hi);
  box.r_hi = int32_t(f.height - 1 - j_lo);
  if (j_hi - j_lo < boxed_rows) box.c_lo = int32_t(c_lo), box.c_hi = int32_t(c_hi);
  return box;
}

// The boxes of a perspective frame's spheres [k0, k0 + n), a block's quadratics solved together.
inline void boxes_of(const float_scene& f, const frame_vectors& fv, uint32_t k0, uint32_t n, double spread, frame_box* out) {
  constexpr uint32_t block = 32;
  const float_spheres& sp = f.spheres;
  for (uint32_t b0 = 0; b0 < n; b0 += block) {
    const uint32_t m = std::min(block, n - b0);
    double wide[block];
    solved rows[block], cols[block];
    for (uint32_t i = 0; i < m; ++i) {
      const sphere_record& e = sp.rec[k0 + b0 + i];
      const double fk[3] = {e.fx, e.fy, e.fz};
      wide[i] = widened(sp, k0 + b0 + i, spread);
      rows[i] = fv.rows.near(fk, wide[i]);
      cols[i] = fv.cols.near(fk, wide[i]);
    }
    for (uint32_t i = 0; i < m; ++i) {
      const uint32_t k = k0 + b0 + i;
      frame_box& box = out[b0 + i];
      box = {1, 0, -1, -1};  // in no row
      const sphere_record& e = sp.rec[k];
      const double fk[3] = {e.fx, e.fy, e.fz}, r = std::sqrt(double(e.r2));
      int64_t j_lo = 0, j_hi = 0, c_lo = 0, c_hi = 0;
      if (!fv.rows.indices(rows[i], j_lo, j_hi)) continue;
      // Outside a sphere, it is hit only ahead, f.d < 0: f.d's least is at a corner (with slack).
      if (dot(fk, fk) > sp.cull_radius[k] * sp.cull_radius[k]) {
        const double least = dot(fk, fv.c) - 0.5 * std::abs(dot(fk, fv.h)) - 0.5 * std::abs(dot(fk, fv.v));
        if (least > (wide[i] - r) * fv.d_len) continue;  // behind every ray: NaN kept
      }
      if (j_hi - j_lo < boxed_rows && !fv.cols.indices(cols[i], c_lo, c_hi)) continue;  // no column's plane comes near
      box.r_lo = int32_t(f.height - 1 - j_hi);
      box.r_hi = int32_t(f.height - 1 - j_lo);
      if (j_hi - j_lo < boxed_rows) box.c_lo = int32_t(c_lo), box.c_hi = int32_t(c_hi);
    }
  }
}

inline frame_box box_of(const float_scene& f, const frame_vectors& fv, uint32_t k, double spread) {
  if (f.orthographic) return box_of_ortho(f, k, spread);
  frame_box box;
  boxes_of(f, fv, k, 1, spread, &box);
  return box;
}

}  // namespace raycast::culling_detail
