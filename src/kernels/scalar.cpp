#include "kernels/scalar.h"

#include <cfloat>
#include <cmath>
#include <cstring>

#include "kernels/newton.h"
#include "kernels/sampled_sky.h"

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace raycast {
namespace {

// The hardware's reciprocal-square-root estimate, as SSE's rsqrtps gives it.
float rsqrt_estimate(float x) {
#if defined(__SSE__) || defined(__x86_64__)
  return _mm_cvtss_f32(_mm_rsqrt_ss(_mm_set_ss(x)));
#else
  return 1.0f / std::sqrt(x);
#endif
}

// max and min as the vector units define them (maxps: a > b ? a : b), so that
// the SIMD backends agree bit for bit, signed zeros included.
float vmax(float a, float b) { return a > b ? a : b; }
float vmin(float a, float b) { return a < b ? a : b; }
float clampf(float x, float lo, float hi) { return vmin(vmax(x, lo), hi); }

}  // namespace

namespace {

struct pixel_dir {
  float dy, n2;
};

pixel_dir direction(const float_scene& f, int64_t i, int64_t j) {
  const float su = pixel_su(f, i), sv = pixel_sv(f, j);
  float d[3];
  for (int k = 0; k < 3; ++k) d[k] = (f.center[k] + su * f.horizontal[k]) + sv * f.vertical[k];
  return {d[1], (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2]};
}

float fast_uy(pixel_dir d) {
  const float n2 = vmax(d.n2, FLT_MIN);
  const float r = rsqrt_estimate(n2);
  const float uy = (d.dy * r) * (fast_nr_a - ((n2 * r) * r) * fast_nr_b);
  return clampf(uy, -1.0f, 1.0f);
}

float exact_t(pixel_dir d) {
  const float uy = d.dy / std::sqrt(vmax(d.n2, FLT_MIN));
  return clampf((uy + 1.0f) * 0.5f, 0.0f, 1.0f);
}

void shade(const float_scene& f, float t, float out[3]) {
  for (int k = 0; k < 3; ++k)
    out[k] = clampf(t == 1.0f ? f.top[k] : f.bottom[k] + t * f.delta[k], f.lo[k], f.hi[k]);
}

// A pixel of a scene with spheres, in kernels/float_spheres.h's order (both
// precisions: fast mode has no sphere path of its own yet).
struct traced {
  float d[3], n2;
  float s, closest;  // the closest hit's s and t
  size_t hit;        // sp.size(): none
};

// The ray with direction d (kernels/float_spheres.h).
traced trace(const float_scene& f, const float (&dir)[3]) {
  traced tr;
  float* d = tr.d;
  for (int k = 0; k < 3; ++k) d[k] = dir[k];
  const float n2 = (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2];
  const float inv_n2 = 1.0f / n2;
  tr.n2 = n2;

  const float_spheres& sp = f.spheres;
  tr.closest = FLT_MAX;
  tr.s = 0.0f;
  tr.hit = sp.size();
  for (size_t k = 0; k < sp.size(); ++k) {
    const float b = (sp.rec[k].fx * d[0] + sp.rec[k].fy * d[1]) + sp.rec[k].fz * d[2];
    float disc;
    if (sp.rec[k].near) {
      disc = b * b - n2 * sp.rec[k].c;
    } else {
      const float kb = b * inv_n2;
      const float vx = sp.rec[k].fx - kb * d[0], vy = sp.rec[k].fy - kb * d[1], vz = sp.rec[k].fz - kb * d[2];
      disc = n2 * (sp.rec[k].r2 - ((vx * vx + vy * vy) + vz * vz));
    }
    const float sq = std::sqrt(vmax(disc, 0.0f));
    const float q = -(b + std::copysign(sq, b));
    const float s0 = sp.rec[k].c / q;
    const float s = s0 >= 0.0f || !sp.rec[k].inside ? s0 : q / n2;
    const float t = s * sp.rec[k].scale;
    if (disc >= 0.0f && s >= 0.0f && t <= tr.closest) {
      tr.closest = t;
      tr.s = s;
      tr.hit = k;
    }
  }
  return tr;
}

// The ray through (su, sv): kernels/scalar.h's direction.
traced trace(const float_scene& f, float su, float sv) {
  float d[3];
  for (int k = 0; k < 3; ++k) d[k] = (f.center[k] + su * f.horizontal[k]) + sv * f.vertical[k];
  return trace(f, d);
}

// The normal of a hit on a normal-shaded sphere: N, facing the ray inside a sphere.
void hit_normal(const float_scene& f, const traced& tr, float n[3]) {
  const float_spheres& sp = f.spheres;
  const size_t hit = tr.hit;
  const float* d = tr.d;
  const float fo[3] = {sp.rec[hit].fx, sp.rec[hit].fy, sp.rec[hit].fz};
  for (int k = 0; k < 3; ++k) n[k] = (fo[k] + tr.s * d[k]) * sp.rec[hit].inv_r;
  if (sp.rec[hit].inside && (n[0] * d[0] + n[1] * d[1]) + n[2] * d[2] >= 0.0f)  // face the ray
    for (int k = 0; k < 3; ++k) n[k] = -n[k];
}

// The colour of a hit (tr.hit < the sphere count): flat, lit, or 0.5 (N + 1).
void hit_color(const float_scene& f, const traced& tr, float out[3]) {
  const float_spheres& sp = f.spheres;
  const size_t hit = tr.hit;
  const float kind = sp.kind_of(hit);
  float n[3];
  if (kind == shading_kind::normal) {
    hit_normal(f, tr, n);
    for (int k = 0; k < 3; ++k) out[k] = (n[k] + 1.0f) * 0.5f;
    return;
  }
  const float albedo[3] = {sp.red[hit], sp.green[hit], sp.blue[hit]};  // there for flat and lit spheres
  if (kind == shading_kind::flat) {
    for (int k = 0; k < 3; ++k) out[k] = albedo[k];
    return;
  }
  hit_normal(f, tr, n);
  const float* d = tr.d;
  const float facing = -((n[0] * d[0] + n[1] * d[1]) + n[2] * d[2]) / std::sqrt(tr.n2);
  const float light = lit_ambient + lit_diffuse * vmax(facing, 0.0f);
  for (int k = 0; k < 3; ++k) out[k] = albedo[k] * light;
}

// The colour of the ray at (su, sv), exact: the closest sphere's shading, else the sky.
void sample_color(const float_scene& f, float su, float sv, float out[3]) {
  const traced tr = trace(f, su, sv);
  if (tr.hit == f.spheres.size()) {
    const float uy = tr.d[1] / std::sqrt(vmax(tr.n2, FLT_MIN));
    shade(f, clampf((uy + 1.0f) * 0.5f, 0.0f, 1.0f), out);
  } else {
    hit_color(f, tr, out);
  }
}

}  // namespace

float pixel_su(const float_scene& f, int64_t i) {
  return f.width == 1 ? 0.0f : (float(i) - f.mid_col) / f.last_col;
}

float pixel_sv(const float_scene& f, int64_t j) {
  return f.height == 1 ? 0.0f : (float(j) - f.mid_row) / f.last_row;
}

void scalar_pixel(const float_scene& f, precision p, int64_t i, int64_t j, float out[3]) {
  if (!f.spheres.empty()) {
    sample_color(f, pixel_su(f, i), pixel_sv(f, j), out);
    return;
  }
  const pixel_dir d = direction(f, i, j);
  const float t = p == precision::exact ? exact_t(d) : (fast_uy(d) + 1.0f) * 0.5f;
  shade(f, t, out);
}

scalar_hit scalar_trace(const float_scene& f, int64_t i, int64_t j) {
  if (f.spheres.empty()) return {};
  const traced tr = trace(f, pixel_su(f, i), pixel_sv(f, j));
  if (tr.hit == f.spheres.size()) return {};
  // P = O + t d in world units, so the distance is t |d|.
  const double d_len = std::sqrt(double(tr.d[0]) * tr.d[0] + double(tr.d[1]) * tr.d[1] +
                                 double(tr.d[2]) * tr.d[2]);
  return {int64_t(tr.hit), double(tr.closest) * d_len};
}

void scalar_pixel_samples(const float_scene& f, const sampling::sample_plan& plan, int64_t i, int64_t j,
                          float out[3]) {
  const float su = pixel_su(f, i), sv = pixel_sv(f, j);
  const float unit = sampling::offset_unit_of(plan.kind);
  const float du = f.du * unit, dv = f.dv * unit;  // exact: a power of two
  float base[3], step_x[3], step_y[3];
  for (int k = 0; k < 3; ++k) {
    base[k] = (f.center[k] + su * f.horizontal[k]) + sv * f.vertical[k];
    step_x[k] = du * f.horizontal[k];
    step_y[k] = dv * f.vertical[k];
  }
  const float_spheres& spheres = f.spheres;
  float flat[3] = {0.0f, 0.0f, 0.0f}, normals[3] = {0.0f, 0.0f, 0.0f}, normal_count = 0.0f;
  float sky_sum = 0.0f, sky_count = 0.0f;
  for (uint32_t s = 0; s < plan.count; ++s) {
    float xi, eta;
    sampling::sample_offset_counts(plan, uint32_t(i), uint32_t(j), s, xi, eta);
    float d[3];
    for (int k = 0; k < 3; ++k) d[k] = (base[k] + xi * step_x[k]) + eta * step_y[k];
    const traced tr = trace(f, d);
    if (tr.hit == spheres.size()) {
      sky_sum = sky_sum + sampling::sky_u<float, uint32_t>(tr.d[1], tr.n2);
      sky_count = sky_count + 1.0f;
    } else if (spheres.kind_of(tr.hit) != shading_kind::normal) {
      float c[3];
      hit_color(f, tr, c);  // the flat or lit colour
      for (int k = 0; k < 3; ++k) flat[k] = flat[k] + c[k];
    } else {
      float n[3];
      hit_normal(f, tr, n);
      for (int k = 0; k < 3; ++k) normals[k] = normals[k] + n[k];
      normal_count = normal_count + 1.0f;
    }
  }
  const float n = float(plan.count);
  for (int k = 0; k < 3; ++k)
    out[k] = ((flat[k] + (normals[k] + normal_count) * 0.5f) + (sky_count * f.sky_mid[k] + sky_sum * f.sky_half[k])) / n;
}

void render_scalar(const float_scene& f, precision p, const image_band& band,
                   const sampling::sample_plan* samples) {
  const int64_t c0 = band.col_begin, c1 = band.cols_end(f.width);
  const bool f32 = band.format == pixel_format::rgb_f32;
  for (int64_t r = band.row_begin; r < band.row_end; ++r) {
    const int64_t j = f.height - 1 - r;
    for (int64_t i = c0; i < c1; ++i) {
      unsigned char* px = band.pixel(r, i);
      float c[3];
      if (samples) {
        scalar_pixel_samples(f, *samples, i, j, c);
      } else if (!f32 && p == precision::fast && f.spheres.empty()) {
        const float uy = fast_uy(direction(f, i, j));
        for (int k = 0; k < 3; ++k)
          px[k] = static_cast<unsigned char>(int(clampf(uy * f.fast_qa[k] + f.fast_qb[k], 0.0f, 255.999f)));
        continue;
      } else {
        scalar_pixel(f, p, i, j, c);
      }
      if (f32) std::memcpy(px, c, sizeof c);
      else
        for (int k = 0; k < 3; ++k) px[k] = static_cast<unsigned char>(int(clampf(c[k], 0.0f, 1.0f) * 255.999f));
    }
  }
}

}  // namespace raycast
