#include "prepare/culling.h"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "prepare/culling_geometry.h"

namespace raycast {

using namespace culling_detail;

namespace {

// Occlusion, for a depth-ordered scene: walked nearest first, each sphere is either hidden (every
// 4x4 tile its box touches is covered by hits nearer than it can be) and left out of the index, or
// kept, and then covers the pixels whose rays surely hit it: those that pass within its sure
// radius (r less twice the culling margin) of the centre of a sphere wholly ahead. A tile's depth
// is the farthest of its pixels' first covering hits, (|f| + r)(1 + 1e-5) in world units (from an
// orthographic camera's plane); a sphere is hidden where its bucket's key (at most |f| - r less
// 2^-15 of it) is beyond that in every tile of its box. Both margins are far above the float
// rounding of t |d|, so a hidden sphere's hit would be strictly farther than the kernel's: no pixel
// changes and no tie involves it. Memory: a byte a pixel, 9 bytes a tile, 8 a column.
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
    // A box of up to 3 x 3 tiles: the farthest of nine (a narrower box's some twice), branch-free
    // (depth_ is never NaN: infinity, or far_, whose std::max in mark() drops a NaN depth).
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

  // Marks the pixels whose rays surely hit sphere k (with samples: all four corners' rays).
  void cover(uint32_t k, const frame_box& b) {
    const sphere_record& e = f_.spheres.rec[k];
    const double r = std::sqrt(double(e.r2)), sure = 2.0 * r - double(f_.spheres.cull_radius[k]);
    if (f_.orthographic) {
      const double scale = e.scale, cx = double(e.fx) * scale, cy = double(e.fy) * scale, cz = double(e.fz) * scale;
      // cz: the depth from the plane the hits' depths and the keys are measured from.
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
    // Rays d = a + su h, a = c + sv v, with |f x d|^2 < sure^2 |d|^2 and f.d < 0: an interval of su.
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
  // The box's rows: where across(sv, s0, s1) gives a row's sure su interval, the pixels inside it
  // (with samples: inside both corner rows' intervals, both corner columns) get depth.
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

  // Covers the row's pixels of the box whose su lies inside (s0, s1).
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
  filled_array<uint8_t> covered_;  // per pixel, rows top-down
  std::vector<uint8_t> open_;     // per tile: its pixels not covered yet
  std::vector<float> far_;        // per tile: the farthest first covering hit
  std::vector<float> depth_;      // per tile: far_ once every pixel is covered, else infinity
};

// Boxes that hold box_of's, without square roots, for spheres [k0, k0 + m), m <= rough_block: ok[i]
// false where empty or too tall. Plane s comes within w of the sphere only where
// |fk.n(s)| = |p1| |s - s_c| <= w n_max: the indices of [s_c - delta, s_c + delta], slack one.
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

struct placed_box {
  uint32_t sphere;
  frame_box box;
};
using placed_boxes = filled_array<placed_box>;

// Spheres [k0, k1)'s boxes, with up to `team` threads, appended to out where in some row.
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
  out.erase(std::remove_if(out.begin() + ptrdiff_t(at), out.end(),
                           [](const placed_box& p) { return p.box.r_lo > p.box.r_hi; }),
            out.end());
}

// The spheres in some row, with their boxes, less those occlusion hides (in depth order, while
// the nearest sixteenth hides an eighth of itself; a lattice seen along its axis hides little).
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
  const int team = n < (size_t(1) << 15) ? 1 : std::max(1, threads);
  const placed_boxes placed = boxes(f, spread, team, ix.hidden);
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
  // Each thread owns rows [r0, r1) and writes only their entries: the bytes do not depend on the team.
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

}  // namespace raycast
