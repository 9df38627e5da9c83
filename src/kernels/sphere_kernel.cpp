// The sphere kernel, written once against the vector layer and compiled per target: a batch is
// vfloat::size pixels of a row, each sphere's record broadcast to every lane, the closest hit kept
// with masks; both precisions give prepare/float_spheres.h's bits. A batch tests only its culling
// list (prepare/culling.h); many samples per pixel run the same batches, a pass a sample.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "kernels/target.inl"  // first: the target's vector layer
#include "kernels/sphere_hit.inl"
#include "kernels/sphere_shade.inl"
#include "kernels/sphere_store.inl"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

// Samples per pass: two overlap their dependency chains where the registers hold both passes.
constexpr int samples_per_pass = vfloats_in_registers >= 16 ? 2 : 1;

// Shortcut `mirror`: a row's leading sky-only batches stored at both ends; returns how many.
template <bool Float, class RaysAt>
int64_t store_mirrored_ends(const float_scene& s, const sky_shader& sky, batch_culler& lists, unsigned char* out,
                            const RaysAt& rays_at) {
  const int64_t W = s.width, batches = (W + N - 1) / N;
  lists.build(0, batches);
  int64_t lead = 0, trail = 0;
  while (lead < batches && lists.tests(lead) == 0) ++lead;
  while (trail < batches - lead && lists.tests(batches - 1 - trail) == 0) ++trail;
  const int64_t sky_from = lead == batches ? 0 : (batches - trail) * N;  // sky to the row's end
  const int64_t by_right = (W - N - sky_from) / N + 1, by_middle = (W - 2 * N) / (2 * N) + 1;
  int64_t ends = W < 2 * N ? 0 : (lead < by_right ? lead : by_right);
  ends = ends < by_middle ? ends : by_middle;
  if (ends < 0) ends = 0;
  for (int64_t b = 0; b < ends; ++b) {
    vfloat c[3];
    sky.shade(rays_at(b * N), c);
    store_batch<Float>(out, b * N, N, c);
    store_batch<Float, true>(out, W - b * N - N, N, c);
  }
  return ends;
}

// The next batch's first candidates, fetched while batch b works (b + 1 in the run [.., b1)).
RAYCAST_INLINE void prefetch_next_batch(const kernel_spheres& sp, const batch_culler& lists, int64_t b, int64_t b1) {
  if (b + 1 >= b1) return;
  if (const size_t n = lists.tests(b + 1)) prefetch_list(sp, lists.list(b + 1), n);
}

template <int Shades, bool Float, bool Lanes, bool Ortho>
void render(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  const float_scene& s = *a.scene;
  const kernel_spheres& sp = a.spheres;
  const sky_shader sky(a);
  const int64_t W = s.width, c0 = band.col_begin, c1 = band.cols_end(W);
  const int64_t batches = (W + N - 1) / N;
  const int64_t first_batch = c0 / N, end_batch = (c1 + N - 1) / N;
  batch_culler lists(s, a.row_most, a.row_shift, N, 0.0);
  const bool cull = a.row_first && lists.ok();  // else every batch tests every sphere
  const bool mirror = a.mirror && cull && band.whole_rows(W);
  for (int64_t r = r0; r < r1; ++r) {
    const int64_t j = s.height - 1 - r;
    const float sv = pixel_sv(s, j);
    if (cull) lists.row(sv, a.row_list + a.row_first[r], size_t(a.row_first[r + 1] - a.row_first[r]));
    const int64_t run = cull ? lists.run_length() : batches;
    const vfloat row_part[3] = {sv * s.vertical[0], sv * s.vertical[1], sv * s.vertical[2]};
    unsigned char* const out = band.row(r);
    // Shortcut `lanes`: every column's d.y and d.z are the first column's (centre + su * 0).
    const float dy = a.column_part[1][0] + sv * s.vertical[1], dz = a.column_part[2][0] + sv * s.vertical[2];
    const vfloat row_y = dy, row_z = dz, row_py = sv * s.plane_height;
    const auto rays_at = [&](int64_t i0) {
      rays ry;
      if constexpr (Ortho) {  // from the image plane (float_scene.h)
        ry.px = vfloat::load(a.ortho_x + i0);
        ry.py = row_py;
      }
      if constexpr (Lanes) {
        ry.d[0] = vfloat::load(a.column_part[0] + i0) + row_part[0];
        ry.d[1] = row_y;
        ry.d[2] = row_z;
      } else {
        for (int k = 0; k < 3; ++k) ry.d[k] = vfloat::load(a.column_part[k] + i0) + row_part[k];
      }
      ry.set_length(s.tiny_directions ? s.centre_unit : nullptr);
      return ry;
    };
    const bool built = mirror && run == batches;  // one run: the whole row's lists at once
    const int64_t ends = built ? store_mirrored_ends<Float>(s, sky, lists, out, rays_at) : 0;
    for (int64_t b0 = ends > first_batch ? ends : first_batch; b0 < end_batch; b0 += run) {
      const int64_t b1 = b0 + run < end_batch ? b0 + run : end_batch;
      if (!built && cull) lists.build(b0, b1);
      for (int64_t b = b0; b < b1; ++b) {
        const int64_t i0 = b * N;
        if (i0 >= W - ends * N) break;  // the mirrored end, already stored
        rays ry = rays_at(i0);
        const size_t tests = cull ? lists.tests(b) : sp.n;
        if (cull) prefetch_next_batch(sp, lists, b, b1);
        vfloat c[3];
        if (tests == 0) {
          sky.shade(ry, c);  // no sphere comes near these rays
        } else {
          closest_hit<Shades> h;
          intersect<Ortho>(sp, cull ? lists.list(b) : nullptr, tests, ry, h);
          shade(sky, sp, h, ry, {i0, j, 0}, c);
        }
        store_window<Float>(out, i0, c0, c1, c);
      }
    }
  }
}

// What every batch of a sampled render shares: scalar.h's steps, and the lesson camera's shortcuts.
template <sampler_kind K>
struct sample_camera {
  vfloat step_x[3], step_y[3];
  // Orthographic: a sample's ray start moves (base[3] + xi step_px, base[4] + eta step_py).
  bool ortho = false;
  vfloat step_px = 0.0f, step_py = 0.0f;
  // The lesson's camera (centre = (+0, +0, -f), horizontal = (h, 0, 0), vertical = (0, v, 0)):
  // scalar.h's d.x = (base.x + xi step_x.x) + eta 0 is base.x + xi step_x.x bit for bit (+0 leaves
  // a sum that is never -0 unchanged), d.y likewise, and d.z = base.z = -f.
  bool lesson = false;
  vfloat z2 = 0.0f;
  // The lesson's camera: each sphere's f.z d.z, once (null: formed per ray, the same bits).
  float* fz_dz = nullptr;
  const float* centre_unit;  // set_length's guard (float_scene::centre_unit)

  sample_camera(const float_scene& s, const kernel_spheres& sp) : centre_unit(s.centre_unit) {
    const float du = s.du * sampling::offset_unit<K>, dv = s.dv * sampling::offset_unit<K>;
    for (int k = 0; k < 3; ++k) {
      step_x[k] = du * s.horizontal[k];
      step_y[k] = dv * s.vertical[k];
    }
    ortho = s.orthographic;
    step_px = du * s.plane_width;
    step_py = dv * s.plane_height;
    lesson = !ortho && s.axis_aligned_camera && s.center[0] == 0.0f && s.center[1] == 0.0f && !std::signbit(s.center[0]) &&
             !std::signbit(s.center[1]) && std::abs(s.center[2]) >= 0x1p-32f;
    z2 = s.center[2] * s.center[2];
    if (lesson) fz_dz = static_cast<float*>(std::malloc(sp.n * sizeof(float) + 1));
    if (fz_dz)
      for (size_t k = 0; k < sp.n; ++k) fz_dz[k] = sp.rec[k].fz * s.center[2];
  }
  ~sample_camera() { std::free(fz_dz); }
  sample_camera(const sample_camera&) = delete;
  sample_camera& operator=(const sample_camera&) = delete;

  // The ray of sample xi, eta (counts of offset_unit) from the pixels' one-sample base.
  RAYCAST_INLINE rays ray(const vfloat base[5], vfloat xi, vfloat eta) const {
    rays ry;
    if (ortho) {
      ry.px = base[3] + xi * step_px;
      ry.py = base[4] + eta * step_py;
    }
    if (lesson) {
      ry.d[0] = base[0] + xi * step_x[0];
      ry.d[1] = base[1] + eta * step_y[1];
      ry.d[2] = base[2];
      ry.n2 = (ry.d[0] * ry.d[0] + ry.d[1] * ry.d[1]) + z2;  // >= z2 >= 2^-64: no guard needed
    } else {
      for (int k = 0; k < 3; ++k) ry.d[k] = (base[k] + xi * step_x[k]) + eta * step_y[k];
      ry.set_length(centre_unit);
    }
    return ry;
  }
};

// M samples t0 .. t0 + M of one batch, each step for all M before the next, summed in order.
// Always inlined (GCC would keep SSE2's two-sample pass out of line).
template <int Shades, sampler_kind K, int M, bool Ortho>
__attribute__((always_inline)) inline void sample_pass(const sampling::sample_plan& plan,
                                                       const sampling::pixel_seeds<vuint>& seeds,
                                                       const sample_camera<K>& cam, const vfloat base[5],
                                                       const kernel_spheres& sp, const uint32_t* list, size_t tests,
                                                       uint32_t t0, const pixel_at& at, sample_sums& sums) {
  rays ry[M];
  for (int u = 0; u < M; ++u) {
    vfloat xi, eta;  // counts of the sampler's offset_unit
    sampling::offset_counts<K>(plan, seeds, t0 + uint32_t(u), xi, eta);
    ry[u] = cam.ray(base, xi, eta);
  }
  if (tests == 0) {  // no sphere comes near these rays
    for (int u = 0; u < M; ++u) sums.add_sky(ry[u]);
    return;
  }
  closest_hit<Shades> h[M];
  // One sphere (most batches that test any): its own copy, where the hit is known to start empty.
  if (tests == 1) intersect<Shades, M, Ortho>(sp, list, 1, ry, h, cam.fz_dz);
  else intersect<Shades, M, Ortho>(sp, list, tests, ry, h, cam.fz_dz);
  for (int u = 0; u < M; ++u) sums.add(sp, h[u], ry[u], {at.i0, at.j, t0 + uint32_t(u)});
}

// Many samples per pixel (kernels/scalar.h): each sample one pass, added to per-lane sums in order.
template <int Shades, sampler_kind K, bool Ortho>
void render_samples(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  const float_scene& s = *a.scene;
  const kernel_spheres& sp = a.spheres;
  const sampling::sample_plan& plan = *a.samples;
  const bool f32 = band.format == pixel_format::rgb_f32;
  const int64_t W = s.width, c0 = band.col_begin, c1 = band.cols_end(W);
  const int64_t batches = (W + N - 1) / N;
  const int64_t first_batch = c0 / N, end_batch = (c1 + N - 1) / N;
  batch_culler lists(s, a.row_most, a.row_shift, N, s.pixel_spread);
  const bool cull = a.row_first && lists.ok();  // else every batch tests every sphere
  const sample_camera<K> cam(s, sp);
  for (int64_t r = r0; r < r1; ++r) {
    const int64_t j = s.height - 1 - r;
    const float sv_j = pixel_sv(s, j);
    if (cull) lists.row(sv_j, a.row_list + a.row_first[r], size_t(a.row_first[r + 1] - a.row_first[r]));
    const int64_t run = cull ? lists.run_length() : batches;
    unsigned char* const out = band.row(r);
    for (int64_t b0 = first_batch; b0 < end_batch; b0 += run) {
      const int64_t b1 = b0 + run < end_batch ? b0 + run : end_batch;
      if (cull) lists.build(b0, b1);
      for (int64_t b = b0; b < b1; ++b) {
        const int64_t i0 = b * N;
        const size_t tests = cull ? lists.tests(b) : sp.n;
        const uint32_t* list = cull && tests > 0 ? lists.list(b) : nullptr;
        if (cull) prefetch_next_batch(sp, lists, b, b1);
        const vuint column = vuint::iota(uint32_t(i0));
        const vfloat su_i = W == 1 ? vfloat(0.0f) : (to_float(column) - s.mid_col) / s.last_col;  // scalar.h
        vfloat base[5];  // the pixels' one-sample directions, and an orthographic ray's start
        for (int k = 0; k < 3; ++k) base[k] = (s.center[k] + su_i * s.horizontal[k]) + sv_j * s.vertical[k];
        base[3] = su_i * s.plane_width;
        base[4] = sv_j * s.plane_height;
        const sampling::pixel_seeds<vuint> seeds = sampling::seeds_for<K>(plan, column, uint32_t(j));
        sample_sums sums;
        uint32_t t = 0;
        const pixel_at at{i0, j, 0};
        for (; t + samples_per_pass <= plan.count; t += samples_per_pass)
          sample_pass<Shades, K, samples_per_pass, Ortho>(plan, seeds, cam, base, sp, list, tests, t, at, sums);
        for (; t < plan.count; ++t) sample_pass<Shades, K, 1, Ortho>(plan, seeds, cam, base, sp, list, tests, t, at, sums);
        vfloat c[3];
        sums.average<Shades>(s, float(plan.count), c);
        if (f32) store_window<true>(out, i0, c0, c1, c);
        else store_window<false>(out, i0, c0, c1, c);
      }
    }
  }
}

template <int Shades, bool Ortho>
void render_sampled(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  switch (a.samples->kind) {
    case sampler_kind::random: render_samples<Shades, sampler_kind::random, Ortho>(a, band, r0, r1); break;
    case sampler_kind::stratified: render_samples<Shades, sampler_kind::stratified, Ortho>(a, band, r0, r1); break;
    case sampler_kind::sobol: render_samples<Shades, sampler_kind::sobol, Ortho>(a, band, r0, r1); break;
  }
}

template <int Shades, bool Ortho>
void render_projection(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  if (a.samples) render_sampled<Shades, Ortho>(a, band, r0, r1);
  else if (band.format == pixel_format::rgb_f32) {
    if (a.lanes) render<Shades, true, true, Ortho>(a, band, r0, r1);
    else render<Shades, true, false, Ortho>(a, band, r0, r1);
  } else {
    if (a.lanes) render<Shades, false, true, Ortho>(a, band, r0, r1);
    else render<Shades, false, false, Ortho>(a, band, r0, r1);
  }
}

template <int Shades>
void render_shades(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  if (a.ortho_x) render_projection<Shades, true>(a, band, r0, r1);
  else render_projection<Shades, false>(a, band, r0, r1);
}

uint32_t scene_index(const float* bits) {
  uint32_t k = 0;
  __builtin_memcpy(&k, bits, sizeof k);
  return k;
}

}  // namespace

scalar_hit trace_pixel(const float_scene& s, const kernel_spheres& sp, int64_t i, int64_t j) {
  const float su = pixel_su(s, i), sv = pixel_sv(s, j);
  rays r;
  for (int k = 0; k < 3; ++k) r.d[k] = (s.center[k] + su * s.horizontal[k]) + sv * s.vertical[k];
  r.set_length(s.centre_unit);
  closest_hit<normal_shading> h;
  if (s.orthographic) {
    r.px = su * s.plane_width;
    r.py = sv * s.plane_height;
    intersect<true>(sp, nullptr, sp.n, r, h);
  } else {
    intersect<false>(sp, nullptr, sp.n, r, h);
  }
  if (none(h.hit)) return {};
  alignas(64) float t[N], d[3][N], index[N];
  store(t, h.t);
  store(index, as_float(h.index));
  for (int k = 0; k < 3; ++k) store(d[k], r.d[k]);
  // The distance is t |d|; orthographic: t is the depth beyond the plane offset.
  const double d_len = std::sqrt(double(d[0][0]) * d[0][0] + double(d[1][0]) * d[1][0] + double(d[2][0]) * d[2][0]);
  if (s.orthographic) return {int64_t(scene_index(index)), double(t[0]) + s.plane_offset};
  return {int64_t(scene_index(index)), double(t[0]) * d_len};
}

void render_sphere_rows(const kernel_args& a, const image_band& band, int64_t r0, int64_t r1) {
  const kernel_spheres& sp = a.spheres;
  if (sp.any_lit) render_shades<all_shadings>(a, band, r0, r1);
  else if (!sp.any_flat) render_shades<normal_shading>(a, band, r0, r1);
  else if (!sp.any_normal) render_shades<flat_shading>(a, band, r0, r1);
  else render_shades<normal_shading | flat_shading>(a, band, r0, r1);
}

}  // namespace raycast::kernels::RAYCAST_ISA
