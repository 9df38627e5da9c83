#include "light/grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace raycast {
namespace {

constexpr double margin = 0x1p-20;       // grid units: the widening of each sphere's box
constexpr size_t max_references = size_t(1) << 31;

// The cells sphere (x, y, z, r) (grid units) overlaps, per axis [c0, c1].
struct cell_range {
  int c0[3], c1[3];
  size_t count() const { return size_t(c1[0] - c0[0] + 1) * size_t(c1[1] - c0[1] + 1) * size_t(c1[2] - c0[2] + 1); }
};

}  // namespace

sphere_grid::sphere_grid(const scene& s, int /*threads*/) {
  const size_t n = s.sphere_count();
  if (n == 0) return;
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = std::numeric_limits<double>::infinity(), hi[a] = -lo[a];
  for (size_t k = 0; k < n; ++k) {
    const raycast::sphere sp = s.sphere_at(k);
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], sp.center[a] - sp.radius);
      hi[a] = std::max(hi[a], sp.center[a] + sp.radius);
    }
  }
  double half = 0;
  for (int a = 0; a < 3; ++a) {
    origin[a] = lo[a] * 0.5 + hi[a] * 0.5;
    half = std::max(half, hi[a] - origin[a]);
  }
  std::frexp(half, &scale_exp);  // half < 2^scale_exp
  spheres_.resize(n * 4);
  for (size_t k = 0; k < n; ++k) {
    const raycast::sphere sp = s.sphere_at(k);
    for (int a = 0; a < 3; ++a) spheres_[k * 4 + a] = float(std::ldexp(sp.center[a] - origin[a], -scale_exp));
    spheres_[k * 4 + 3] = float(std::ldexp(sp.radius, -scale_exp));
  }
  // Grid units: the box lies within [-1, 1]. About one cell per sphere.
  double size[3], volume = 1;
  for (int a = 0; a < 3; ++a) {
    lo_[a] = float(std::ldexp(lo[a] - origin[a], -scale_exp) - 2 * margin);
    size[a] = std::ldexp(hi[a] - lo[a], -scale_exp) + 4 * margin;
    volume *= size[a];
  }
  double h = std::cbrt(volume / double(n));
  const auto range_of = [&](size_t k) {
    cell_range r;
    const float* sp = sphere(uint32_t(k));
    for (int a = 0; a < 3; ++a) {
      const double x0 = (double(sp[a]) - sp[3] - margin - lo_[a]) / h, x1 = (double(sp[a]) + sp[3] + margin - lo_[a]) / h;
      r.c0[a] = std::clamp(int(std::floor(x0)), 0, dims_[a] - 1);
      r.c1[a] = std::clamp(int(std::floor(x1)), 0, dims_[a] - 1);
    }
    return r;
  };
  for (;;) {  // coarser until the references fit
    for (int a = 0; a < 3; ++a) dims_[a] = int(std::clamp(std::ceil(size[a] / h), 1.0, double(1 << 20)));
    size_t total = 0;
    for (size_t k = 0; k < n && total <= max_references; ++k) total += range_of(k).count();
    if (total <= max_references && total <= 64 * n + 4096) break;
    h *= 2;
  }
  h_ = float(h);
  inv_h_ = float(1.0 / h);
  for (int a = 0; a < 3; ++a) hi_[a] = lo_[a] + float(dims_[a]) * h_;
  const size_t cells = size_t(dims_[0]) * size_t(dims_[1]) * size_t(dims_[2]);
  first_.assign(cells + 1, 0);
  const auto each_cell = [&](const cell_range& r, auto&& f) {
    for (int z = r.c0[2]; z <= r.c1[2]; ++z)
      for (int y = r.c0[1]; y <= r.c1[1]; ++y)
        for (int x = r.c0[0]; x <= r.c1[0]; ++x) f(size_t(x) + size_t(dims_[0]) * (size_t(y) + size_t(dims_[1]) * size_t(z)));
  };
  for (size_t k = 0; k < n; ++k) each_cell(range_of(k), [&](size_t c) { ++first_[c + 1]; });
  for (size_t c = 0; c < cells; ++c) first_[c + 1] += first_[c];
  refs_.resize(first_[cells]);
  std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
  for (size_t k = 0; k < n; ++k) each_cell(range_of(k), [&](size_t c) { refs_[fill[c]++] = uint32_t(k); });
}

bool sphere_grid::cell_occluded(size_t cell, const float o[3], const float d[3], float tmax, uint32_t skip) const {
  for (uint32_t e = first_[cell]; e < first_[cell + 1]; ++e) {
    const uint32_t k = refs_[e];
    if (k == skip) continue;
    const float* s = sphere(k);
    const float ox = o[0] - s[0], oy = o[1] - s[1], oz = o[2] - s[2];
    const float r2 = s[3] * s[3];
    if ((ox * ox + oy * oy) + oz * oz <= r2) return true;  // the ray starts inside it
    const float b = (ox * d[0] + oy * d[1]) + oz * d[2];
    if (b >= 0.0f) continue;  // outside, and moving away
    // Hearn and Baker: the squared distance of the line from the centre, no
    // cancellation against |o - c|^2.
    const float vx = ox - b * d[0], vy = oy - b * d[1], vz = oz - b * d[2];
    const float m2 = (vx * vx + vy * vy) + vz * vz;
    if (m2 > r2) continue;
    if (-b - std::sqrt(r2 - m2) <= tmax) return true;
  }
  return false;
}

bool sphere_grid::occluded(const float o[3], const float d[3], float tmax, uint32_t skip) const {
  if (refs_.empty()) return false;
  // The segment clipped to the grid's box (a hit point starts inside it:
  // no clipping, the walk ends where it leaves the box).
  float t0 = 0.0f, t1 = tmax, inv[3];
  bool inside = true;
  for (int a = 0; a < 3; ++a) {
    inv[a] = d[a] == 0.0f ? std::numeric_limits<float>::infinity() : 1.0f / d[a];
    inside = inside && o[a] >= lo_[a] && o[a] < hi_[a];
  }
  for (int a = 0; a < 3 && !inside; ++a) {
    if (d[a] == 0.0f) {
      if (o[a] < lo_[a] || o[a] > hi_[a]) return false;
      continue;
    }
    float ta = (lo_[a] - o[a]) * inv[a], tb = (hi_[a] - o[a]) * inv[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1)) return false;
  // Amanatides and Woo's walk, each boundary's t computed afresh (no sum of
  // steps drifts across a long ray).
  int c[3], step[3];
  float next[3];
  size_t stride[3] = {1, size_t(dims_[0]), size_t(dims_[0]) * size_t(dims_[1])};
  size_t cell = 0;
  for (int a = 0; a < 3; ++a) {
    c[a] = std::clamp(int(std::floor((o[a] + t0 * d[a] - lo_[a]) * inv_h_)), 0, dims_[a] - 1);
    step[a] = d[a] > 0.0f ? 1 : -1;
    next[a] = d[a] == 0.0f ? std::numeric_limits<float>::infinity()
                           : (lo_[a] + float(c[a] + (step[a] > 0)) * h_ - o[a]) * inv[a];
    cell += size_t(c[a]) * stride[a];
  }
  for (;;) {
    if (cell_occluded(cell, o, d, tmax, skip)) return true;
    const int a = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
    if (next[a] > t1) return false;
    c[a] += step[a];
    if (c[a] < 0 || c[a] >= dims_[a]) return false;
    cell = step[a] > 0 ? cell + stride[a] : cell - stride[a];
    next[a] = (lo_[a] + float(c[a] + (step[a] > 0)) * h_ - o[a]) * inv[a];
  }
}

}  // namespace raycast
