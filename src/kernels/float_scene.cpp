#include "kernels/float_scene.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace raycast {

float_scene prepare_float_scene(const scene& s) {
  const camera& c = s.cam;
  float_scene f;
  f.width = c.image_width;
  f.height = c.image_height;
  f.last_col = float(c.image_width - 1);
  f.last_row = float(c.image_height - 1);
  f.mid_col = float(double(c.image_width - 1) / 2.0);
  f.mid_row = float(double(c.image_height - 1) / 2.0);
  const vec3 centre = -c.focal_length * c.axis_w;
  f.du = c.image_width == 1 ? 0.0f : 1.0f / f.last_col;
  f.dv = c.image_height == 1 ? 0.0f : 1.0f / f.last_row;

  double m = 0.0;
  for (const vec3& v : {centre, c.horizontal, c.vertical})
    m = std::max({m, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  int e = 0;
  std::frexp(m, &e);  // m = x * 2^e with x in [0.5, 1)
  const double scale = std::ldexp(1.0, -e);
  // Values below 2^-64 (camera components relative to the largest, and sky
  // colours) become 0. They cannot change a float result, but as denormals
  // somewhere in the arithmetic they could make the output depend on the
  // FTZ/DAZ bits; above 2^-64 no product or sum in scalar.h is denormal.
  const auto flush = [](double x) { return std::abs(x) < 0x1p-64 ? 0.0f : float(x); };
  for (int k = 0; k < 3; ++k) {
    f.centre[k] = flush(centre[k] * scale);
    f.horizontal[k] = flush(c.horizontal[k] * scale);
    f.vertical[k] = flush(c.vertical[k] * scale);
    f.bottom[k] = flush(s.sky.bottom[k]) + 0.0f;  // + 0: a -0 colour becomes +0
    f.top[k] = flush(s.sky.top[k]) + 0.0f;
    f.delta[k] = f.top[k] - f.bottom[k];
    const double half = 0.5 * (double(f.top[k]) - double(f.bottom[k]));
    f.fast_qa[k] = float(255.999 * half);
    f.fast_qb[k] = float(255.999 * (double(f.bottom[k]) + half));
    f.sky_mid[k] = float(double(f.bottom[k]) + 0.5 * double(f.delta[k]));
    f.sky_half[k] = float(0.5 * double(f.delta[k]));
    f.lo[k] = std::min(f.bottom[k], f.top[k]);
    f.hi[k] = std::max(f.bottom[k], f.top[k]);
  }
  {  // the viewport's plane is at distance |centre| (horizontal and vertical
     // are orthogonal to it), so every direction is at least that long
    const auto len = [](const float* v) {
      return std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
    };
    f.pixel_spread = 1.01 * (len(f.horizontal) * f.du + len(f.vertical) * f.dv) / len(f.centre);
  }
  f.axis_aligned_camera = f.horizontal[1] == 0 && f.horizontal[2] == 0 && f.vertical[0] == 0 &&
                   f.vertical[2] == 0;

  // Per-sphere constants in double, each rounded to float once
  // (kernels/float_spheres.h).
  float_spheres& sp = f.spheres;
  for (const sphere& b : s.spheres) {
    const vec3 fo = c.origin - b.center;
    // The sphere's own unit, 2^e: max(|f|, r) 2^-e in [0.5, 1) (exact in
    // double for every finite scene; the float constants then neither
    // overflow nor underflow but for radii below 2^-126 of the distance).
    const double size = std::max({std::abs(fo.x), std::abs(fo.y), std::abs(fo.z), b.radius});
    int unit = 0;
    std::frexp(size, &unit);
    const double down = std::ldexp(1.0, -unit);
    const vec3 fs = fo * down;
    const double r = b.radius * down;
    const double f2 = fs.x * fs.x + fs.y * fs.y + fs.z * fs.z;
    const double cc = f2 - r * r;
    sp.fx.push_back(float(fs.x));
    sp.fy.push_back(float(fs.y));
    sp.fz.push_back(float(fs.z));
    sp.c.push_back(float(cc));
    sp.r2.push_back(float(r * r));
    sp.inv_r.push_back(float(1.0 / r));
    sp.scale.push_back(float(std::ldexp(1.0, unit)));
    sp.near.push_back(f2 < 2.0 * r * r ? 1 : 0);
    sp.inside.push_back(cc <= 0.0 ? 1 : 0);
    {  // from the float constants, as the renderers see the sphere
      const double ff[3] = {sp.fx.back(), sp.fy.back(), sp.fz.back()};
      const double rf = std::sqrt(double(sp.r2.back()));
      sp.cull_radius.push_back(rf + 1e-4 * (std::sqrt(ff[0] * ff[0] + ff[1] * ff[1] + ff[2] * ff[2]) + rf));
    }
    sp.any_inside = sp.any_inside || sp.inside.back();
    const bool flat = b.shade == shading::flat;
    sp.red.push_back(flat ? flush(b.flat_color.r) + 0.0f : 0.0f);
    sp.green.push_back(flat ? flush(b.flat_color.g) + 0.0f : 0.0f);
    sp.blue.push_back(flat ? flush(b.flat_color.b) + 0.0f : 0.0f);
    sp.flat.push_back(flat ? 1.0f : 0.0f);
    sp.any_flat = sp.any_flat || flat;
    sp.any_normal = sp.any_normal || !flat;
  }
  return f;
}

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

// Where alpha x^2 + 2 beta x + gamma <= 0, as an interval [s0, s1]: left
// unbounded (as given) where that set is not one bounded interval (alpha <= 0,
// or NaN), false where it is empty.
bool below_zero(double alpha, double beta, double gamma, double& s0, double& s1) {
  if (!(alpha > 0.0)) return true;
  const double disc = beta * beta - alpha * gamma;
  if (disc < 0.0) return false;
  if (!(disc >= 0.0)) return true;
  // The roots, without cancellation.
  const double q = -(beta + std::copysign(std::sqrt(disc), beta));
  s0 = q / alpha;
  s1 = q != 0.0 ? gamma / q : s0;
  if (s0 > s1) std::swap(s0, s1);
  return true;
}

// The indices i in [0, count) with (i - mid) / last in [s0, s1] (a column
// from su, a row from sv: kernels/scalar.h), widened by slack each way, as
// [lo, hi]; false when there is none.
bool index_range(double s0, double s1, float last, float mid, double slack, int64_t count, int64_t& lo,
                 int64_t& hi) {
  const double i0 = std::floor(s0 * double(last) + double(mid)) - slack;
  const double i1 = std::ceil(s1 * double(last) + double(mid)) + slack;
  if (i1 < 0.0 || i0 > double(count - 1) || i0 > i1) return false;
  lo = i0 > 0.0 ? int64_t(i0) : 0;  // (NaN: 0)
  hi = i1 < double(count - 1) ? int64_t(i1) : count - 1;
  return true;
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
  const double f2 = double(sp.fx[k]) * sp.fx[k] + double(sp.fy[k]) * sp.fy[k] + double(sp.fz[k]) * sp.fz[k];
  return sp.cull_radius[k] + spread * std::sqrt(f2);
}

}  // namespace

bool sphere_rows(const float_scene& f, uint32_t k, int64_t& j_lo, int64_t& j_hi, double spread) {
  const float_spheres& sp = f.spheres;
  j_lo = 0;
  j_hi = f.height - 1;
  // Row sv's plane has the normal (centre + sv vertical) x horizontal = N0 +
  // sv N1; the sphere is near where (f.n)^2 <= w^2 |n|^2, a quadratic in sv.
  double c[3], v[3], h[3], N0[3], N1[3];
  for (int i = 0; i < 3; ++i) {
    c[i] = f.centre[i];
    v[i] = f.vertical[i];
    h[i] = f.horizontal[i];
  }
  cross(c, h, N0);
  cross(v, h, N1);
  const double fk[3] = {sp.fx[k], sp.fy[k], sp.fz[k]};
  const double w = widened(sp, k, spread), w2 = w * w;
  const double p0 = dot(fk, N0), p1 = dot(fk, N1);
  double s0 = -INFINITY, s1 = INFINITY;
  if (!below_zero(p1 * p1 - w2 * dot(N1, N1), p0 * p1 - w2 * dot(N0, N1), p0 * p0 - w2 * dot(N0, N0), s0, s1))
    return false;
  if (f.height == 1) return true;  // one row: the plane test decides
  // sv = (j - mid_row) / last_row; two rows of slack each way.
  return index_range(s0, s1, f.last_row, f.mid_row, 2.0, f.height, j_lo, j_hi);
}

size_t spheres_in_row(const float_scene& f, float sv, int batch, sphere_span* out,
                      const uint32_t* candidates, size_t n_candidates, double spread) {
  const float_spheres& sp = f.spheres;
  const int64_t last_batch = (f.width - 1) / batch;
  size_t count = 0;
  // The row's plane through the camera origin, spanned by a = centre + sv *
  // vertical (as scalar.h's direction, in double) and horizontal; n its normal.
  row_rays rr;
  for (int k = 0; k < 3; ++k) {
    rr.a[k] = double(f.centre[k]) + double(sv) * double(f.vertical[k]);
    rr.h[k] = double(f.horizontal[k]);
  }
  double n[3];
  cross(rr.a, rr.h, n);
  const double len = std::sqrt(dot(n, n));
  const bool plane = len > 0.0 && std::isfinite(len);  // else a degenerate row: no plane test
  const double d_len = std::sqrt(dot(rr.a, rr.a)) + std::sqrt(dot(rr.h, rr.h));  // >= |d| in the row
  const size_t considered = candidates ? n_candidates : sp.size();
  for (size_t x = 0; x < considered; ++x) {
    const uint32_t k = candidates ? candidates[x] : uint32_t(x);
    const double fk[3] = {sp.fx[k], sp.fy[k], sp.fz[k]};
    // The margin (in cull_radius): 1e-4 of |f| + r, hundreds of times the
    // float intersection's rounding (and the direction's, about 1e-7 of |f|),
    // so that leaving a sphere out never changes a pixel.
    const double wide = widened(sp, k, spread);
    if (plane && std::abs(dot(fk, n)) > wide * len) continue;  // NaN: kept
    int64_t lo = 0, hi = f.width - 1;
    const double ahead_slack = (wide - std::sqrt(double(sp.r2[k]))) * d_len;
    const bool outside = dot(fk, fk) > sp.cull_radius[k] * sp.cull_radius[k];
    if (!columns_near(f, rr, fk, wide, outside, ahead_slack, lo, hi)) continue;
    out[count++] = {k, int32_t(std::min(lo / batch, last_batch)), int32_t(std::min(hi / batch, last_batch))};
  }
  return count;
}

}  // namespace raycast
