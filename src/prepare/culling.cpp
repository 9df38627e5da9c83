#include "prepare/culling.h"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <utility>

namespace raycast {

namespace {

// Rays of a row: d(su) = a + su h, su in [-1/2, 1/2] (scalar.h, in double).
struct row_rays {
  double a[3], h[3];
};

double dot(const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }

void cross(const double* x, const double* y, double* out) {
  out[0] = x[1] * y[2] - x[2] * y[1];
  out[1] = x[2] * y[0] - x[0] * y[2];
  out[2] = x[0] * y[1] - x[1] * y[0];
}

// Where alpha x^2 + 2 beta x + gamma <= 0: empty, one bounded interval
// [s0, s1], or not one bounded interval (alpha <= 0, or NaN: unbounded).
// Without branches, so that many spheres' square roots and divisions overlap
// (boxes_of).
struct solved {
  enum : uint8_t { empty, bounded, unbounded };
  double s0, s1;
  uint8_t kind;
};
inline solved solve_below_zero(double alpha, double beta, double gamma) {
  const double disc = beta * beta - alpha * gamma;
  // The roots, without cancellation.
  const double q = -(beta + std::copysign(std::sqrt(disc), beta));
  const double r0 = q / alpha, r1 = q != 0.0 ? gamma / q : r0;
  const bool open = !(alpha > 0.0) || std::isnan(disc);
  return {r0 > r1 ? r1 : r0, r0 > r1 ? r0 : r1,
          uint8_t(open ? solved::unbounded : disc < 0.0 ? solved::empty : solved::bounded)};
}

// solve_below_zero's as an interval [s0, s1]: left as given where unbounded,
// false where empty.
bool below_zero(double alpha, double beta, double gamma, double& s0, double& s1) {
  const solved r = solve_below_zero(alpha, beta, gamma);
  if (r.kind == solved::bounded) s0 = r.s0, s1 = r.s1;
  return r.kind != solved::empty;
}

// The indices [i0, i1] (whole numbers in double) clamped to [0, count) as
// [lo, hi]; false when none is inside.
bool clamp_indices(double i0, double i1, int64_t count, int64_t& lo, int64_t& hi) {
  if (i1 < 0.0 || i0 > double(count - 1) || i0 > i1) return false;
  lo = i0 > 0.0 ? int64_t(i0) : 0;  // (NaN: 0)
  hi = i1 < double(count - 1) ? int64_t(i1) : count - 1;
  return true;
}

// The indices i in [0, count) with (i - mid) / last in [s0, s1] (a column
// from su, a row from sv: kernels/scalar.h), widened by slack each way, as
// [lo, hi]; false when there is none.
bool index_range(double s0, double s1, float last, float mid, double slack, int64_t count, int64_t& lo,
                 int64_t& hi) {
  const double i0 = std::floor(s0 * double(last) + double(mid)) - slack;
  const double i1 = std::ceil(s1 * double(last) + double(mid)) + slack;
  return clamp_indices(i0, i1, count, lo, hi);
}

// The columns [lo, hi] of the row whose rays come within r of the sphere's
// centre (f = O - C, both in the sphere's unit). Their lines do where
// |f x d|^2 <= r^2 |d|^2, a quadratic in su; and where the camera is outside
// the sphere (`outside`: outside its unwidened culling radius, even when it is
// within the widened r -- the ground seen by rays that stray a pixel), a ray
// (s >= 0, not the whole line) also needs the centre ahead, f.d <= 0, linear
// in su (here with slack m, which covers the stray). False when no column's does.
bool columns_near(const float_scene& fs, const row_rays& rr, const double* f, double r, bool outside, double m,
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
  // su = (i - mid_col) / last_col; one column of slack each way.
  return index_range(s0, s1, fs.last_col, fs.mid_col, 1.0, fs.width, lo, hi);
}

// The sphere's culling radius for rays that may stray by spread (float_scene.h).
double widened(const float_spheres& sp, uint32_t k, double spread) {
  if (spread == 0.0) return sp.cull_radius[k];
  const double f2 = double(sp.rec[k].fx) * sp.rec[k].fx + double(sp.rec[k].fy) * sp.rec[k].fy + double(sp.rec[k].fz) * sp.rec[k].fz;
  return sp.cull_radius[k] + spread * std::sqrt(f2);
}

// An orthographic camera's rays are lines across the view, one per pixel's
// plane position (px, py) = (su plane_width, sv plane_height): sphere k's
// centre and reach on the plane in world units, its culling radius widened
// by a sample's lateral stray (the pixel_spread is lateral there).
struct plane_disc {
  double cx, cy, w;
  bool behind;  // entirely behind the image plane: no ray meets it
};
plane_disc disc_of(const float_scene& f, uint32_t k, double spread) {
  const sphere_record& e = f.spheres.rec[k];
  const double scale = e.scale, w = (f.spheres.cull_radius[k] + spread / scale) * scale;
  return {double(e.fx) * scale, double(e.fy) * scale, w, double(e.fz) * scale + f.plane_offset + w < 0.0};
}

// The indices whose plane position (s = (i - mid) / last, times extent) lies
// within [lo, hi], with a slack of one each way; false when none does.
bool plane_range(double lo, double hi, double extent, float last, float mid, int64_t count, int64_t& a, int64_t& b) {
  if (count == 1) {
    a = b = 0;
    return lo <= 0.0 && hi >= 0.0;
  }
  return index_range(lo / extent, hi / extent, last, mid, 1.0, count, a, b);
}

// A family of planes through the camera origin: plane s is spanned by
// a + s step and along, with s = (i - mid) / last for index i -- the rows'
// planes (step = vertical, along = horizontal) or the columns' (the other way
// round). Plane s has the normal N0 + s N1 (N0 = a x along, N1 = step x
// along); the products of the normals are the frame's, computed once.
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

  // The indices i in [0, count) whose plane may come near the sphere at fk
  // (within w): where (fk.n)^2 <= w^2 |n|^2, a quadratic in s, in double; the
  // indices rounded outwards (the radius's margin covers the float rounding
  // of s). False when none is near.
  bool range(const double* fk, double w, int64_t& lo, int64_t& hi) const { return indices(near(fk, w), lo, hi); }
  // range() in two steps: the quadratic's solution, then its indices.
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

// Per row, what the exact test of a sphere against the row's rays needs.
struct row_test {
  const float_scene& f;
  double spread;
  row_rays rr;
  double n[3], len = 0.0, d_len = 0.0;
  bool plane = false;

  float sv;

  row_test(const float_scene& fs, float sv_, double spread_) : f(fs), spread(spread_), sv(sv_) {
    // The row's plane through the camera origin, spanned by a = centre + sv *
    // vertical (as scalar.h's direction, in double) and horizontal; n its normal.
    for (int k = 0; k < 3; ++k) {
      rr.a[k] = double(f.center[k]) + double(sv) * double(f.vertical[k]);
      rr.h[k] = double(f.horizontal[k]);
    }
    cross(rr.a, rr.h, n);
    len = std::sqrt(dot(n, n));
    plane = len > 0.0 && std::isfinite(len);  // else a degenerate row: no plane test
    d_len = std::sqrt(dot(rr.a, rr.a)) + std::sqrt(dot(rr.h, rr.h));  // >= |d| in the row
  }

  // The columns [lo, hi] of the row whose rays may hit sphere k; false when none.
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
    // The margin (in cull_radius): 1e-5 of |f| + r, a hundred times the
    // float intersection's rounding (and the direction's, about 1e-7 of |f|),
    // so that leaving a sphere out never changes a pixel.
    const double wide = widened(sp, k, spread);
    if (plane && std::abs(dot(fk, n)) > wide * len) return false;  // NaN: kept
    lo = 0;
    hi = f.width - 1;
    const double ahead_slack = (wide - std::sqrt(double(sp.rec[k].r2))) * d_len;
    const bool outside = dot(fk, fk) > sp.cull_radius[k] * sp.cull_radius[k];
    return columns_near(f, rr, fk, wide, outside, ahead_slack, lo, hi);
  }
};

// The index keeps a sphere's column box for spheres at most this many rows
// tall: a box wider than the sphere in its top and bottom rows costs a few
// spare tests there, far less than an exact test per row. Taller spheres get
// the exact test in each row they cross (row_test).
constexpr int64_t boxed_rows = 64;

// A sphere's place in the frame: its rows and, for a short one, its columns.
// (No member initializers: the frame's array of them is filled, not zeroed first.)
struct frame_box {
  int32_t r_lo, r_hi;  // rows, top-down (r = H - 1 - j); empty when r_lo > r_hi
  int32_t c_lo, c_hi;  // columns; -1: tested per row
};

frame_box box_of_ortho(const float_scene& f, uint32_t k, double spread) {
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

// The boxes of spheres [k0, k0 + n) of a perspective camera's frame, into
// out: a block of spheres at a time, their quadratics solved together (no
// branch between one sphere's square roots and divisions and the next's).
void boxes_of(const float_scene& f, const frame_vectors& fv, uint32_t k0, uint32_t n, double spread, frame_box* out) {
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
      // A sphere the camera is outside of is hit only ahead, f.d < 0; f.d is
      // linear over the viewport, so its least value is at a corner (rays that
      // stray a pixel are covered by the slack, as in columns_near).
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

frame_box box_of(const float_scene& f, const frame_vectors& fv, uint32_t k, double spread) {
  if (f.orthographic) return box_of_ortho(f, k, spread);
  frame_box box;
  boxes_of(f, fv, k, 1, spread, &box);
  return box;
}

// Occlusion, for a depth-ordered scene (float_spheres::depth_key): its
// spheres come nearest first, and a sphere every ray of whose box surely hits
// a nearer one first cannot be seen, so it is left out of the index (a packed
// box seen from outside hides most of its spheres behind a few layers).
// Walked in the scene's order, each sphere is either hidden -- every 4x4
// tile its box touches is covered, and by hits nearer than it can be -- or
// kept, and then marks the pixels whose rays surely hit it: rays that pass
// within its radius less twice the culling margin (its sure radius) of the
// centre, of a sphere wholly ahead. A tile's depth is the farthest of its
// pixels' first covering hits, |f| + r (from the plane an orthographic
// camera's depths are measured from; world units, and 1e-5 more); a sphere is
// hidden when its nearest distance (its bucket's key, at most |f| - r less
// 2^-15 of it) is beyond that depth in every tile of its box. Both margins
// are far above the float intersection's rounding of t |d|, so a hidden
// sphere's hit would be strictly farther than one the kernel finds: leaving
// it out changes no pixel, and no tie can involve it. Memory, while the index
// is built: a byte a pixel, 9 bytes a tile, 8 a column.
class occlusion {
 public:
  static constexpr int64_t T = 4;  // a tile's side, in pixels
  occlusion(const float_scene& f, double spread)
      : f_(f), spread_(spread), tw_((f.width + T - 1) / T), th_((f.height + T - 1) / T), su_(size_t(f.width)),
        covered_(size_t(f.width * f.height), 0),
        open_(size_t(tw_ * th_)), far_(size_t(tw_ * th_), 0.0f), depth_(size_t(tw_ * th_), INFINITY) {
    for (int64_t ty = 0; ty < th_; ++ty)
      for (int64_t tx = 0; tx < tw_; ++tx)
        open_[size_t(ty * tw_ + tx)] = uint8_t(std::min<int64_t>(T, f.height - T * ty) * std::min<int64_t>(T, f.width - T * tx));
    for (int k = 0; k < 3; ++k) h_[k] = f.horizontal[k], c_[k] = f.center[k], v_[k] = f.vertical[k];
    for (int64_t i = 0; i < f.width; ++i) su_[size_t(i)] = pixel_su(f, i);
  }

  // Whether every tile of the box is covered by hits nearer than `nearest`.
  bool hidden(const frame_box& b, float nearest) const {
    const int64_t tx0 = b.c_lo / T, tx1 = b.c_hi / T, ty0 = b.r_lo / T, ty1 = b.r_hi / T;
    // A box of up to 3 x 3 tiles (nearly every sphere's in a deep scene):
    // the farthest of all nine (a narrower box's some twice), with no
    // branch (depth_ is never NaN: infinity, or far_, whose
    // std::max(far_, depth) in mark() drops a NaN depth).
    // The loop below, whose count and exit vary from sphere to sphere, made
    // the occlusion walk of a packed box of 10^6 take 6 % longer.
    if (tx1 - tx0 < 3 && ty1 - ty0 < 3) {
      const float* row[3] = {&depth_[size_t(ty0 * tw_)], &depth_[size_t(std::min(ty0 + 1, ty1) * tw_)],
                             &depth_[size_t(ty1 * tw_)]};
      const int64_t col[3] = {tx0, std::min(tx0 + 1, tx1), tx1};
      float far = row[0][col[0]];
      for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) far = std::max(far, row[y][col[x]]);
      return far < nearest;
    }
    for (int64_t ty = b.r_lo / T; ty <= b.r_hi / T; ++ty)
      for (int64_t tx = b.c_lo / T; tx <= b.c_hi / T; ++tx)
        if (!(depth_[size_t(ty * tw_ + tx)] < nearest)) return false;
    return true;
  }

  // Marks the pixels of sphere k's box whose rays surely hit it. With many
  // samples (spread > 0), a pixel's sample rays lie between its corners'
  // (kernels/scalar.h: the offsets are in [0, 1) of a pixel), and the rays
  // that surely hit a sphere form a convex set (a cone, or a disc on an
  // orthographic camera's plane): the pixel is covered where its four
  // corners' rays are.
  void cover(uint32_t k, const frame_box& b) {
    const sphere_record& e = f_.spheres.rec[k];
    const double r = std::sqrt(double(e.r2)), sure = 2.0 * r - double(f_.spheres.cull_radius[k]);
    if (f_.orthographic) {
      const double scale = e.scale, cx = double(e.fx) * scale, cy = double(e.fy) * scale, cz = double(e.fz) * scale;
      // cz: the depth from the plane the hits' depths (and the keys) are
      // measured from, plane_offset ahead of the image plane.
      const double margin = 1e-5 * (std::abs(cx) + std::abs(cy) + std::abs(cz) + r * scale);
      if (!(sure > 0.0) || !(cz + f_.plane_offset - r * scale > margin)) return;
      const double w = sure * scale;
      const auto across = [&](double sv, double& s0, double& s1) {  // the disc on the plane's line
        const double dy = sv * f_.plane_height - cy;
        if (!(std::abs(dy) < w)) return false;
        const double half = std::sqrt(w * w - dy * dy);
        s0 = (cx - half) / f_.plane_width, s1 = (cx + half) / f_.plane_width;
        return true;
      };
      return cover_rows(b, float(cz + r * scale + margin), across);
    }
    if (e.inside || e.near || !(sure > 0.0)) return;
    const double fk[3] = {e.fx, e.fy, e.fz}, len = std::sqrt(dot(fk, fk));
    double B[3];
    cross(fk, h_, B);
    const double s2 = sure * sure, bb = dot(B, B), hh = dot(h_, h_), fh = dot(fk, h_);
    // Rays d = a + su h, a = c + sv v, with |f x d|^2 < sure^2 |d|^2 (a
    // quadratic in su) and f.d < 0 (linear): an interval of su.
    const auto across = [&](double sv, double& s0, double& s1) {
      const double a[3] = {c_[0] + sv * v_[0], c_[1] + sv * v_[1], c_[2] + sv * v_[2]};
      double A[3];
      cross(fk, a, A);
      s0 = INFINITY, s1 = -INFINITY;  // left so where the set is no bounded interval: no rays
      if (!below_zero(bb - s2 * hh, dot(A, B) - s2 * dot(a, h_), dot(A, A) - s2 * dot(a, a), s0, s1) ||
          !std::isfinite(s0) || !std::isfinite(s1))
        return false;
      const double fa = dot(fk, a);
      if (fh > 0.0) s1 = std::min(s1, -fa / fh);
      else if (fh < 0.0) s0 = std::max(s0, -fa / fh);
      else if (!(fa < 0.0)) return false;
      return true;
    };
    cover_rows(b, float((len + r) * double(e.scale) * (1.0 + 1e-5)), across);
  }

 private:
  // The box's rows: where across(sv, s0, s1) gives the su interval (s0, s1)
  // of a row's sure rays, the pixels inside it (with samples: the pixel's
  // two corner rows' intervals, both corners' columns) are covered at depth.
  template <class Across>
  void cover_rows(const frame_box& b, float depth, const Across& across) {
    const bool corners = spread_ > 0.0;
    const double du = corners ? double(f_.du) : 0.0, dv = corners ? double(f_.dv) : 0.0;
    for (int64_t row = b.r_lo; row <= b.r_hi; ++row) {
      const double sv = pixel_sv(f_, f_.height - 1 - row);
      double s0 = 0, s1 = 0, t0 = 0, t1 = 0;  // empty unless across() sets them
      if (!across(sv, s0, s1)) continue;
      if (corners) {
        if (!across(sv + dv, t0, t1)) continue;
        s0 = std::max(s0, t0), s1 = std::min(s1, t1) - du;
      }
      mark(row, b, s0, s1, depth);
    }
  }

  // Covers the row's pixels of the box whose su lies inside (s0, s1). (The
  // ends' rounding is far below the sure radius's margin.)
  void mark(int64_t row, const frame_box& b, double s0, double s1, float depth) {
    if (!(s0 < s1)) return;
    const double w = double(f_.width), last = f_.last_col, mid = f_.mid_col;
    int64_t i0 = std::max<int64_t>(b.c_lo, int64_t(std::clamp(std::floor(s0 * last + mid), 0.0, w)));
    int64_t i1 = std::min<int64_t>(b.c_hi, int64_t(std::clamp(std::ceil(s1 * last + mid), -1.0, w - 1.0)));
    while (i0 <= i1 && !(su_[size_t(i0)] > s0)) ++i0;
    while (i1 >= i0 && !(su_[size_t(i1)] < s1)) --i1;
    for (int64_t col = i0; col <= i1; ++col) {
      const size_t p = size_t(row * f_.width + col);
      if (covered_[p]) continue;
      covered_[p] = 1;
      const size_t t = size_t((row / T) * tw_ + col / T);
      far_[t] = std::max(far_[t], depth);
      if (--open_[t] == 0) depth_[t] = far_[t];
    }
  }

  const float_scene& f_;
  double spread_;
  int64_t tw_, th_;
  double h_[3], c_[3], v_[3];
  std::vector<double> su_;         // per column (kernels/scalar.h)
  // Per pixel, rows top-down; from a megabyte on, in huge pages where they
  // fault in faster (memory/pages.h: a 4 KiB page's first touch costs
  // 10 us on some hosts: 500 of them for a 1920 x 1080 frame).
  filled_array<uint8_t> covered_;
  std::vector<uint8_t> open_;     // per tile: its pixels not covered yet
  std::vector<float> far_;        // per tile: the farthest first covering hit
  std::vector<float> depth_;      // per tile: far_ once every pixel is covered, else infinity
};

// Boxes that hold box_of's, cheaper (no square root), for the spheres
// [k0, k0 + m), m <= rough_block: ok[i] false where a box is empty or too
// tall to be worth a test. For each family of planes (rows, columns), plane
// s comes within w of the sphere only where |fk.n(s)| = |p1| |s - s_c| <=
// w |n(s)| <= w n_max, s_c the plane through the centre; the indices of
// [s_c - delta, s_c + delta] with a slack of one each way (index_range's).
// The block's arithmetic comes first, in loops with no branch, then its
// boxes: a sphere at a time, this took twice as long (branches between one
// sphere's divisions and the next's).
constexpr uint32_t rough_block = 32;
void rough_boxes(const float_scene& f, const frame_vectors& fv, uint32_t k0, uint32_t m, double spread, frame_box* box,
                 bool* ok) {
  double fx[rough_block], fy[rough_block], fz[rough_block], wide[rough_block];
  for (uint32_t i = 0; i < m; ++i) {
    const sphere_record& e = f.spheres.rec[k0 + i];
    fx[i] = e.fx, fy[i] = e.fy, fz[i] = e.fz, wide[i] = widened(f.spheres, k0 + i, spread);
  }
  const plane_family* family[2] = {&fv.rows, &fv.cols};
  double lo[2][rough_block], hi[2][rough_block];
  bool whole[2][rough_block];  // every index: one plane, or p1 = 0
  for (int a = 0; a < 2; ++a) {
    const plane_family& P = *family[a];
    const double n0[3] = {P.N0[0], P.N0[1], P.N0[2]}, n1[3] = {P.N1[0], P.N1[1], P.N1[2]};
    const double n_max = P.n_max, last = P.last, mid = P.mid;
    for (uint32_t i = 0; i < m; ++i) {  // dot(fk, N0), dot(fk, N1)
      const double p0 = fx[i] * n0[0] + fy[i] * n0[1] + fz[i] * n0[2], p1 = fx[i] * n1[0] + fy[i] * n1[1] + fz[i] * n1[2];
      const double inv = 1.0 / p1, s_c = -p0 * inv, delta = wide[i] * n_max * std::abs(inv);
      whole[a][i] = P.count == 1 || !(std::abs(p1) > 0.0);
      lo[a][i] = (s_c - delta) * last + mid;
      hi[a][i] = (s_c + delta) * last + mid;
    }
    for (uint32_t i = 0; i < m; ++i) lo[a][i] = std::floor(lo[a][i]) - 1.0, hi[a][i] = std::ceil(hi[a][i]) + 1.0;
  }
  for (uint32_t i = 0; i < m; ++i) {
    int64_t r[2][2];
    ok[i] = true;
    for (int a = 0; a < 2 && ok[i]; ++a) {
      r[a][0] = 0, r[a][1] = family[a]->count - 1;
      if (!whole[a][i]) ok[i] = clamp_indices(lo[a][i], hi[a][i], family[a]->count, r[a][0], r[a][1]);
      if (a == 0 && r[0][1] - r[0][0] >= boxed_rows) ok[i] = false;
    }
    if (ok[i]) box[i] = {int32_t(f.height - 1 - r[0][1]), int32_t(f.height - 1 - r[0][0]), int32_t(r[1][0]), int32_t(r[1][1])};
  }
}

// A sphere in some row of the frame, and its box.
struct placed_box {
  uint32_t sphere;
  frame_box box;
};
using placed_boxes = filled_array<placed_box>;

// Spheres [k0, k1)'s boxes (box_of), with up to `team` threads, appended to
// out where they are in some row.
void append_boxes(const float_scene& f, const frame_vectors& fv, double spread, int team, size_t k0, size_t k1,
                  placed_boxes& out) {
  const size_t at = out.size();
  out.resize(at + (k1 - k0));
  constexpr size_t chunk = 1024;
#pragma omp parallel for schedule(static) num_threads(team)
  for (size_t c0 = k0; c0 < k1; c0 += chunk) {
    const size_t c1 = std::min(k1, c0 + chunk);
    frame_box box[chunk];
    if (f.orthographic)
      for (size_t k = c0; k < c1; ++k) box[k - c0] = box_of_ortho(f, uint32_t(k), spread);
    else
      boxes_of(f, fv, uint32_t(c0), uint32_t(c1 - c0), spread, box);
    for (size_t k = c0; k < c1; ++k) out[at + (k - k0)] = {uint32_t(k), box[k - c0]};
  }
  // The spheres in no row out, the others kept in their order.
  out.erase(std::remove_if(out.begin() + ptrdiff_t(at), out.end(),
                           [](const placed_box& p) { return p.box.r_lo > p.box.r_hi; }),
            out.end());
}

// The spheres in some row of the frame, in the float scene's order, with
// their boxes (box_of). In a depth-ordered scene, the spheres occlusion
// hides are left out too (rough boxes first: most of a deep scene's
// spheres are hidden, and need no exact box); `hidden` counts them. Where
// the nearest sixteenth of the spheres hides less than an eighth of itself
// (a lattice seen along its axis, whose gaps let every tile see through),
// the rest are boxed as in any other scene.
placed_boxes boxes(const float_scene& f, double spread, int team, size_t& hidden) {
  const size_t n = f.spheres.size();
  const frame_vectors fv(f);
  placed_boxes out;
  hidden = 0;
  if (f.spheres.depth_key.empty() || f.tiny_directions) {
    append_boxes(f, fv, spread, team, 0, n, out);
    return out;
  }
  occlusion occ(f, spread);
  const size_t check = std::max<size_t>(n / 16, 4096);
  frame_box rough[rough_block];
  bool rough_ok[rough_block] = {};
  for (size_t k = 0; k < n; ++k) {
    if (k == check && hidden < k / 8) {
      append_boxes(f, fv, spread, team, k, n, out);
      break;
    }
    const uint32_t i = uint32_t(k % rough_block);
    if (i == 0 && !f.orthographic)
      rough_boxes(f, fv, uint32_t(k), uint32_t(std::min<size_t>(rough_block, n - k)), spread, rough, rough_ok);
    const float nearest = f.spheres.depth_key[f.spheres.rec[k].depth];
    if (!f.orthographic && rough_ok[i] && occ.hidden(rough[i], nearest)) {
      ++hidden;
      continue;
    }
    const frame_box b = box_of(f, fv, uint32_t(k), spread);
    if (b.r_lo > b.r_hi) continue;  // in no row
    if (b.c_lo >= 0) {  // tall spheres are kept, and cover nothing
      if (occ.hidden(b, nearest)) {
        ++hidden;
        continue;
      }
      occ.cover(uint32_t(k), b);
    }
    out.push_back({uint32_t(k), b});
  }
  return out;
}

}  // namespace

bool sphere_rows(const float_scene& f, uint32_t k, int64_t& j_lo, int64_t& j_hi, double spread) {
  if (f.orthographic) {
    const plane_disc d = disc_of(f, k, spread);
    return !d.behind && plane_range(d.cy - d.w, d.cy + d.w, f.plane_height, f.last_row, f.mid_row, f.height, j_lo, j_hi);
  }
  const float_spheres& sp = f.spheres;
  const double fk[3] = {sp.rec[k].fx, sp.rec[k].fy, sp.rec[k].fz};
  return frame_vectors(f).rows.range(fk, widened(sp, k, spread), j_lo, j_hi);
}

size_t spheres_in_row(const float_scene& f, float sv, int batch, sphere_span* out,
                      const uint32_t* candidates, size_t n_candidates, double spread) {
  const int64_t last_batch = (f.width - 1) / batch;
  const row_test row(f, sv, spread);
  size_t count = 0;
  const size_t considered = candidates ? n_candidates : f.spheres.size();
  for (size_t x = 0; x < considered; ++x) {
    const uint32_t k = candidates ? candidates[x] : uint32_t(x);
    int64_t lo = 0, hi = 0;
    if (row.columns(k, lo, hi))
      out[count++] = {k, int32_t(std::min(lo / batch, last_batch)), int32_t(std::min(hi / batch, last_batch))};
  }
  return count;
}

row_index row_index::build(const float_scene& f, double spread, int threads) {
  const size_t n = f.spheres.size();
  const int64_t H = f.height;
  row_index ix;
  ix.first.assign(size_t(H) + 1, 0);
  if (n == 0) return ix;
  // Below this many spheres a thread costs more than it saves.
  const int team = n < (size_t(1) << 15) ? 1 : std::max(1, threads);
  const placed_boxes placed = boxes(f, spread, team, ix.hidden);
  // Counts per row from a difference array, then their prefix sums.
  std::vector<int64_t> diff(size_t(H) + 1, 0);
  for (const placed_box& p : placed) ++diff[size_t(p.box.r_lo)], --diff[size_t(p.box.r_hi) + 1];
  int64_t running = 0;
  for (int64_t r = 0; r < H; ++r) {
    running += diff[size_t(r)];
    ix.most = std::max(ix.most, size_t(running));
    ix.first[size_t(r) + 1] = ix.first[size_t(r)] + uint64_t(running);
  }
  ix.list.resize(ix.first.back());
  while (((f.width - 1) >> ix.shift) >= row_entry::tall) ++ix.shift;
  const int shift = ix.shift;
  // Filled in the float scene's order by row blocks: each thread owns rows [r0, r1), scans
  // every sphere's rows and writes only its own rows' entries, so the bytes
  // do not depend on the team and no two threads write the same row.
#pragma omp parallel num_threads(team)
  {
    const int t = omp_get_thread_num(), p = omp_get_num_threads();
    const int64_t r0 = H * t / p, r1 = H * (t + 1) / p;
    std::vector<uint64_t> cursor(ix.first.begin() + r0, ix.first.begin() + r1);
    for (const placed_box& pb : placed) {
      const frame_box& b = pb.box;
      const int64_t lo = std::max<int64_t>(b.r_lo, r0), hi = std::min<int64_t>(b.r_hi, r1 - 1);
      if (lo > hi) continue;
      const row_entry e = b.c_lo < 0 ? row_entry{pb.sphere, row_entry::tall, 0}
                                     : row_entry{pb.sphere, uint16_t(b.c_lo >> shift), uint16_t(b.c_hi >> shift)};
      for (int64_t r = lo; r <= hi; ++r) ix.list[cursor[size_t(r - r0)]++] = e;
    }
  }
  return ix;
}

batch_culler::batch_culler(const float_scene& f, size_t most, int shift, int batch, double spread)
    : f_(f), shift_(shift), batch_shift_(std::countr_zero(unsigned(batch))), spread_(spread),
      batches_((f.width + batch - 1) / batch) {
  assert(std::has_single_bit(unsigned(batch)));  // a vector's width: batch_shift_ divides by it
  spans_ = static_cast<sphere_span*>(std::malloc(most * sizeof(sphere_span) + 1));
  capacity_ = std::max(4 * most, budget);
  const size_t batches = size_t(batches_);
  list_ = static_cast<uint32_t*>(std::malloc(capacity_ * sizeof(uint32_t)));
  first_ = static_cast<uint32_t*>(std::malloc((batches + 1) * sizeof(uint32_t)));
  fill_ = static_cast<uint32_t*>(std::malloc((batches + 1) * sizeof(uint32_t)));
  count_ = static_cast<uint32_t*>(std::malloc(batches * sizeof(uint32_t)));
  slot_start_ = static_cast<uint32_t*>(std::malloc(batches * sizeof(uint32_t)));
  if (!spans_ || !list_ || !first_ || !fill_ || !count_ || !slot_start_) {
    release();
    return;
  }
  // Slots share the list's memory: a batch's slot is touched only as far
  // as its list reaches, so a long slot costs no cache.
  slot_ = std::min<size_t>(capacity_ / batches, UINT32_MAX / batches);
  for (size_t b = 0; b < batches; ++b) slot_start_[b] = uint32_t(b * slot_);
}

batch_culler::~batch_culler() { release(); }

void batch_culler::release() {
  std::free(spans_);
  std::free(list_);
  std::free(first_);
  std::free(fill_);
  std::free(count_);
  std::free(slot_start_);
  spans_ = nullptr;
  list_ = first_ = fill_ = count_ = slot_start_ = nullptr;
}

namespace {

// Each of a row's entries whose sphere its rays may come near, as keep(k,
// lo, hi) with the columns [lo, hi] (a tall sphere's from the exact test,
// made at the first); stops, false, where keep returns false.
template <class Keep>
bool each_entry(const float_scene& f, float sv, double spread, int shift, const row_entry* entries, size_t count,
                const Keep& keep) {
  std::optional<row_test> exact;
  for (size_t x = 0; x < count; ++x) {
    const row_entry& e = entries[x];
    int64_t lo = int64_t(e.lo) << shift, hi = ((int64_t(e.hi) + 1) << shift) - 1;
    if (e.lo == row_entry::tall) {
      if (!exact) exact.emplace(f, sv, spread);
      if (!exact->columns(e.sphere, lo, hi)) continue;
    }
    if (!keep(e.sphere, lo, hi)) return false;
  }
  return true;
}

}  // namespace

size_t batch_culler::row(float sv, const row_entry* entries, size_t count) {
  b0_ = 0;
  if (row_in_slots(sv, entries, count)) return kept_;
  // A slot would overflow (a batch listing more than slot_ spheres: rare,
  // spheres that each cover much of the frame): the spans, which build()
  // counts and then places.
  const int64_t last_batch = batches_ - 1;
  kept_ = 0;
  entries_ = 0;
  start_ = first_;
  each_entry(f_, sv, spread_, shift_, entries, count, [&](uint32_t k, int64_t lo, int64_t hi) {
    const int32_t a = int32_t(std::min(lo >> batch_shift_, last_batch)), b = int32_t(std::min(hi >> batch_shift_, last_batch));
    spans_[kept_++] = {k, a, b};
    entries_ += size_t(b - a + 1);
    return true;
  });
  return kept_;
}

bool batch_culler::row_in_slots(float sv, const row_entry* entries, size_t count) {
  slotted_ = false;
  if (slot_ == 0) return false;
  const int64_t last_batch = batches_ - 1;
  std::fill(count_, count_ + batches_, 0u);
  kept_ = 0;
  // lo, hi >= 0: a shift is the division by the batch's width (an integer
  // division per end was half the row's time).
  const bool fit = each_entry(f_, sv, spread_, shift_, entries, count, [&](uint32_t k, int64_t lo, int64_t hi) {
    const int64_t a = std::min(lo >> batch_shift_, last_batch), b = std::min(hi >> batch_shift_, last_batch);
    ++kept_;
    if (b - a <= 1) {  // most spheres: one batch or two, written with no branch between them
      // Room for the second write too, which lands one past the list's end
      // (and is not counted) where b = a.
      if (count_[a] + 1 >= slot_ || count_[b] + 1 >= slot_) return false;
      list_[slot_start_[a] + count_[a]++] = k;
      list_[slot_start_[b] + count_[b]] = k;
      count_[b] += uint32_t(b != a);
      return true;
    }
    for (int64_t i = a; i <= b; ++i) {
      if (count_[i] == slot_) return false;
      list_[slot_start_[i] + count_[i]++] = k;
    }
    return true;
  });
  if (!fit) return false;
  slotted_ = true;
  start_ = slot_start_;
  return true;
}

int64_t batch_culler::run_length() const {
  if (slotted_ || entries_ <= capacity_) return batches_;  // the whole row at once
  const int64_t most = int64_t(capacity_ / kept_);
  return std::clamp<int64_t>(most, 1, batches_);
}

void batch_culler::build(int64_t b0, int64_t b1) {
  if (slotted_) return;  // made by row(), for every batch (b0_ = 0)
  b0_ = b0;
  if (kept_ == 0) return;
  const int64_t n = b1 - b0;
  std::fill(fill_, fill_ + n + 1, 0u);
  // A span's batches within the run, as [a, b].
  const auto clip = [b0, b1](const sphere_span& s, int64_t& a, int64_t& b) {
    a = std::max<int64_t>(s.lo, b0);
    b = std::min<int64_t>(s.hi, b1 - 1);
  };
  for (size_t x = 0; x < kept_; ++x) {
    int64_t a = 0, b = 0;
    clip(spans_[x], a, b);
    for (int64_t i = a; i <= b; ++i) ++fill_[i - b0 + 1];
  }
  first_[0] = 0;
  for (int64_t i = 0; i < n; ++i) {
    first_[i + 1] = first_[i] + fill_[i + 1];
    count_[i] = fill_[i + 1];
    fill_[i] = first_[i];
  }
  for (size_t x = 0; x < kept_; ++x) {
    int64_t a = 0, b = 0;
    clip(spans_[x], a, b);
    for (int64_t i = a; i <= b; ++i) list_[fill_[i - b0]++] = spans_[x].sphere;
  }
}

}  // namespace raycast
