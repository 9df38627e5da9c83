#include "kernels/float_scene.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

namespace raycast {
namespace {

// Values below 2^-64 (camera components relative to the largest, and sky
// colours) become 0. They cannot change a float result, but as denormals
// somewhere in the arithmetic they could make the output depend on the
// FTZ/DAZ bits; above 2^-64 no product or sum in scalar.h is denormal.
float flush(double x) { return std::abs(x) < 0x1p-64 ? 0.0f : float(x); }

// The camera and the sky, scaled and rounded once (float_scene.h).
void prepare_camera(float_scene& f, const scene& s) {
  const camera& c = s.cam;
  f.width = c.image_width;
  f.height = c.image_height;
  f.last_col = float(c.image_width - 1);
  f.last_row = float(c.image_height - 1);
  f.mid_col = float(double(c.image_width - 1) / 2.0);
  f.mid_row = float(double(c.image_height - 1) / 2.0);
  const vec3 center = -c.focal_length * c.axis_w;
  f.du = c.image_width == 1 ? 0.0f : 1.0f / f.last_col;
  f.dv = c.image_height == 1 ? 0.0f : 1.0f / f.last_row;

  double m = 0.0;
  for (const vec3& v : {center, c.horizontal, c.vertical})
    m = std::max({m, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  int e = 0;
  std::frexp(m, &e);  // m = x * 2^e with x in [0.5, 1)
  const double scale = std::ldexp(1.0, -e);
  for (int k = 0; k < 3; ++k) {
    f.center[k] = flush(center[k] * scale);
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
    f.pixel_spread = 1.01 * (len(f.horizontal) * f.du + len(f.vertical) * f.dv) / len(f.center);
  }
  f.axis_aligned_camera = f.horizontal[1] == 0 && f.horizontal[2] == 0 && f.vertical[0] == 0 &&
                   f.vertical[2] == 0;
}

// std::frexp's exponent and std::ldexp(1, e) and std::nextafter(x, INFINITY),
// from the bits where the value is a normal number, else by the library:
// the same results without a library call per sphere (a sixth of the
// per-sphere constants' time here).
int exponent_of(double x) {  // x = m 2^e with m in [0.5, 1)
  const uint64_t bits = std::bit_cast<uint64_t>(x);
  const int biased = int((bits >> 52) & 0x7ff);
  if (biased == 0 || biased == 0x7ff) {
    int e = 0;
    std::frexp(x, &e);
    return e;
  }
  return biased - 1022;
}
double power_of_two(int e) {
  if (e < -1022 || e > 1023) return std::ldexp(1.0, e);
  return std::bit_cast<double>(uint64_t(e + 1023) << 52);
}
float next_up(float x) {  // for x >= +0
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  if (!(x >= 0.0f) || bits >= 0x7f800000u) return std::nextafter(x, INFINITY);
  return std::bit_cast<float>(bits + 1);
}

// One sphere's constants in double, each rounded to float once
// (float_spheres.h).
sphere_record record_of(const sphere& b, const point3& origin) {
  const vec3 fo = origin - b.center;
  // The sphere's own unit, 2^e: max(|f|, r) 2^-e in [0.5, 1) (exact in
  // double for every finite scene; the float constants then neither
  // overflow nor underflow but for radii below 2^-126 of the distance).
  const double size = std::max({std::abs(fo.x), std::abs(fo.y), std::abs(fo.z), b.radius});
  const int unit = exponent_of(size);
  const double down = power_of_two(-unit);
  const vec3 fs = fo * down;
  const double r = b.radius * down;
  const double f2 = fs.x * fs.x + fs.y * fs.y + fs.z * fs.z;
  const double cc = f2 - r * r;
  sphere_record e{};
  e.fx = float(fs.x);
  e.fy = float(fs.y);
  e.fz = float(fs.z);
  e.c = float(cc);
  e.r2 = float(r * r);
  e.inv_r = float(1.0 / r);
  e.scale = float(power_of_two(unit));
  e.near = f2 < 2.0 * r * r ? 1 : 0;
  e.inside = cc <= 0.0 ? 1 : 0;
  return e;
}

// Its culling radius: from the float constants, as the renderers see the
// sphere; rounded up.
float cull_radius_of(const sphere_record& e) {
  const double ff[3] = {e.fx, e.fy, e.fz};
  const double rf = std::sqrt(double(e.r2));
  const double wide = rf + 1e-5 * (std::sqrt(ff[0] * ff[0] + ff[1] * ff[1] + ff[2] * ff[2]) + rf);
  return next_up(float(wide));
}

// The image row (0 at the top) of a sphere's centre as the camera sees it,
// clamped to the image; H for a centre not in front of the camera: the key
// of a large scene's order (prepare_float_scene).
uint32_t centre_row(const camera& c, const point3& center) {
  using glm::dot;
  const int64_t H = c.image_height;
  const vec3 p = center - c.origin;
  const double ahead = -dot(p, c.axis_w);  // the distance along the view
  const double sv = dot(p, c.vertical) / dot(c.vertical, c.vertical) * (c.focal_length / ahead);  // -1/2 .. 1/2
  const double j = sv * double(H - 1) + 0.5 * double(H - 1);  // from the bottom, as kernels/scalar.h
  if (!(ahead > 0.0) || !(j == j)) return uint32_t(H);
  return uint32_t(H - 1 - std::clamp<int64_t>(std::llround(std::clamp(j, -1.0, double(H))), 0, H - 1));
}

// The order of the float scene: sphere order[i] of the scene is the float
// scene's i-th, stably sorted by their centre_row keys (a counting sort).
using index_array = std::vector<uint32_t, huge_page_allocator<uint32_t>>;
index_array row_order(const index_array& key, size_t H) {
  const size_t n = key.size();
  index_array order(n);
  std::vector<size_t> first(H + 2, 0);
  for (uint32_t r : key) ++first[r + 1];
  for (size_t r = 0; r <= H; ++r) first[r + 1] += first[r];
  for (size_t k = 0; k < n; ++k) order[first[key[k]]++] = uint32_t(k);
  return order;
}

// a[i] = a[order[i]] for every i, through a second array.
template <class T>
void reorder(float_spheres::array<T>& a, const index_array& order, int team) {
  float_spheres::array<T> sorted(a.size());
#pragma omp parallel for schedule(static) num_threads(team)
  for (size_t i = 0; i < a.size(); ++i) sorted[i] = a[order[i]];
  a.swap(sorted);
}

}  // namespace

float_scene prepare_float_scene(const scene& s, int threads, size_t sort_from) {
  const camera& c = s.cam;
  float_scene f;
  prepare_camera(f, s);

  // Per-sphere constants in double, each rounded to float once
  // (kernels/float_spheres.h); in parallel for large scenes (each sphere's
  // are its own, so the bytes do not depend on the threads).
  float_spheres& sp = f.spheres;
  const size_t n = s.sphere_count();
  sp.rec.resize(n);
  const int team = n < (size_t(1) << 15) ? 1 : std::max(1, threads);
  const bool sorted = n >= sort_from;
  index_array key(sorted ? n : 0);
  bool any_inside = false, any_flat = false, any_normal = false, any_lit = false;
#pragma omp parallel for schedule(static) num_threads(team) reduction(|| : any_inside, any_flat, any_normal, any_lit)
  for (size_t k = 0; k < n; ++k) {
    const sphere b = s.sphere_at(k);  // a vector's, or a caller's arrays'
    if (sorted) key[k] = centre_row(c, b.center);
    const sphere_record& e = sp.rec[k] = record_of(b, c.origin);
    any_inside = any_inside || e.inside;
    any_flat = any_flat || b.shade == shading::flat;
    any_lit = any_lit || b.shade == shading::lit;
    any_normal = any_normal || b.shade == shading::normal;
  }
  sp.any_inside = any_inside;
  sp.any_flat = any_flat;
  sp.any_normal = any_normal;
  sp.any_lit = any_lit;
  // Colours only where some sphere has one: a second pass, which a cloud of
  // normal-shaded spheres (13 bytes a sphere) does without.
  const bool colored = any_flat || any_lit;
  if (colored) {
    sp.red.resize(n);
    sp.green.resize(n);
    sp.blue.resize(n);
    sp.kind.resize(n);
#pragma omp parallel for schedule(static) num_threads(team)
    for (size_t k = 0; k < n; ++k) {
      const sphere b = s.sphere_at(k);
      const bool flat = b.shade == shading::flat, lit = b.shade == shading::lit;
      sp.red[k] = flat || lit ? flush(b.flat_color.r) + 0.0f : 0.0f;
      sp.green[k] = flat || lit ? flush(b.flat_color.g) + 0.0f : 0.0f;
      sp.blue[k] = flat || lit ? flush(b.flat_color.b) + 0.0f : 0.0f;
      sp.kind[k] = flat ? shading_kind::flat : lit ? shading_kind::lit : shading_kind::normal;
    }
  }
  // Reordered after, not read in order: a caller's spheres are read front to
  // back (read out of order from small pages, a virtual machine's TLB misses
  // cost microseconds a sphere), the gather reads our own arrays.
  if (sorted) {
    const index_array order = row_order(key, size_t(c.image_height));
    index_array().swap(key);
    reorder(sp.rec, order, team);
    if (colored) {
      reorder(sp.red, order, team);
      reorder(sp.green, order, team);
      reorder(sp.blue, order, team);
      reorder(sp.kind, order, team);
    }
  }
  // The culling radii, from the records in their final order.
  sp.cull_radius.resize(n);
#pragma omp parallel for schedule(static) num_threads(team)
  for (size_t k = 0; k < n; ++k) sp.cull_radius[k] = cull_radius_of(sp.rec[k]);
  return f;
}

}  // namespace raycast
