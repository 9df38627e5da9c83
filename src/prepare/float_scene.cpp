#include "prepare/float_scene.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

namespace raycast {
namespace {

// Sky colours below 2^-64 become 0: they change no result, but as denormals could depend on FTZ.
float flush(double x) { return std::abs(x) < 0x1p-64 ? 0.0f : float(x); }

// Camera components below 2^-100 of the largest become 0: above it every su * component is normal
// (|su| >= 2^-24). An all-tiny direction survives: max(n2, FLT_MIN) in the sky, set_length's scaling.
float flush_camera(double x) { return std::abs(x) < 0x1p-100 ? 0.0f : float(x); }

void prepare_camera(float_scene& f, const scene& s) {
  const camera& c = s.cam;
  f.width = c.image_width;
  f.height = c.image_height;
  f.last_col = float(c.image_width - 1);
  f.last_row = float(c.image_height - 1);
  f.mid_col = float(double(c.image_width - 1) / 2.0);
  f.mid_row = float(double(c.image_height - 1) / 2.0);
  const bool ortho = c.proj == projection::orthographic;
  const vec3 center = ortho ? -c.axis_w : -c.focal_length * c.axis_w;
  const vec3 horizontal = ortho ? vec3(0.0) : c.horizontal, vertical = ortho ? vec3(0.0) : c.vertical;
  f.du = c.image_width == 1 ? 0.0f : 1.0f / f.last_col;
  f.dv = c.image_height == 1 ? 0.0f : 1.0f / f.last_row;

  double m = 0.0;
  for (const vec3& v : {center, horizontal, vertical})
    m = std::max({m, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  int e = 0;
  std::frexp(m, &e);  // m = x * 2^e with x in [0.5, 1)
  const double scale = std::ldexp(1.0, -e);
  for (int k = 0; k < 3; ++k) {
    f.center[k] = flush_camera(center[k] * scale);
    f.horizontal[k] = flush_camera(horizontal[k] * scale);
    f.vertical[k] = flush_camera(vertical[k] * scale);
    f.axes[0][k] = float(c.axis_u[k]);
    f.axes[1][k] = float(c.axis_v[k]);
    f.axes[2][k] = float(-c.axis_w[k]);
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
  {  // the viewport's plane is |centre| away, so every direction is at least that long
    const auto len = [](const float* v) {
      return std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
    };
    f.pixel_spread = 1.01 * (len(f.horizontal) * f.du + len(f.vertical) * f.dv) / len(f.center);
  }
  if (ortho) {  // the spread is lateral: one pixel across, in world units
    f.orthographic = true;
    f.plane_width = float(c.viewport_width);
    f.plane_height = float(c.viewport_height);
    f.pixel_spread = 1.01 * (c.viewport_width * double(f.du) + c.viewport_height * double(f.dv));
  }
  const double cm = std::max({std::abs(center.x), std::abs(center.y), std::abs(center.z)});
  for (int k = 0; k < 3; ++k) f.centre_unit[k] = cm > 0.0 ? flush_camera(center[k] / cm) : 0.0f;
  f.tiny_directions = (double(f.center[0]) * f.center[0] + double(f.center[1]) * f.center[1] +
                       double(f.center[2]) * f.center[2]) < 0x1p-60;
  f.axis_aligned_camera = f.horizontal[1] == 0 && f.horizontal[2] == 0 && f.vertical[0] == 0 &&
                   f.vertical[2] == 0;
}

// std::frexp's exponent, std::ldexp(1, e), std::nextafter(x, INFINITY): from the bits where normal.
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

// One sphere's constants in double, each rounded to float once (float_spheres.h); in its own unit
// they neither overflow nor underflow but for radii below 2^-126 of the distance.
sphere_record record_of(const sphere& b, const point3& origin) {
  const vec3 fo = origin - to_glm(b.center);
  const double size = std::max({std::abs(fo.x), std::abs(fo.y), std::abs(fo.z), b.radius});
  const int unit = exponent_of(size);
  const double down = power_of_two(-unit);
  const vec3 fs = fo * down;
  const double r = b.radius * down;
  const double f2 = fs.x * fs.x + fs.y * fs.y + fs.z * fs.z;
  const double cc = f2 - r * r;
  return {.fx = float(fs.x), .fy = float(fs.y), .fz = float(fs.z), .c = float(cc), .r2 = float(r * r),
          .inv_r = float(1.0 / r), .scale = float(power_of_two(unit)), .near = uint8_t(f2 < 2.0 * r * r ? 1 : 0),
          .inside = uint8_t(cc <= 0.0 ? 1 : 0), .depth = 0};
}

// The same for an orthographic camera (float_spheres.h): c holds 2^-e; `inside`: the image plane
// cuts the sphere or it lies behind (a ray may start inside it: its far root, or no hit).
sphere_record record_of_ortho(const sphere& b, const camera& cam, double z0) {
  const vec3 p = to_glm(b.center) - cam.origin;
  const double cx = glm::dot(p, cam.axis_u), cy = glm::dot(p, cam.axis_v), depth = -glm::dot(p, cam.axis_w);
  const double cz = depth - z0;
  const int unit = exponent_of(std::max({std::abs(cx), std::abs(cy), std::abs(cz), b.radius}));
  const double down = power_of_two(-unit), r = b.radius * down;
  return {.fx = float(cx * down), .fy = float(cy * down), .fz = float(cz * down), .c = float(down),
          .r2 = float(r * r), .inv_r = float(1.0 / r), .scale = float(power_of_two(unit)), .near = 0,
          .inside = uint8_t(depth - b.radius < 0.0 ? 1 : 0), .depth = 0};
}

// Its culling radius, from the float constants as the renderers see the sphere; rounded up.
float cull_radius_of(const sphere_record& e) {
  const double ff[3] = {e.fx, e.fy, e.fz};
  const double rf = std::sqrt(double(e.r2));
  const double wide = rf + 1e-5 * (std::sqrt(ff[0] * ff[0] + ff[1] * ff[1] + ff[2] * ff[2]) + rf);
  return next_up(float(wide));
}

// The rows order's key: the image row (0 at the top) of a sphere's centre, clamped; H if not ahead.
uint32_t centre_row(const camera& c, const point3& center) {
  using glm::dot;
  const int64_t H = c.image_height;
  const vec3 p = center - c.origin;
  const double ahead = -dot(p, c.axis_w);  // the distance along the view
  const bool ortho = c.proj == projection::orthographic;  // the plane's row under the centre
  const double sv = dot(p, c.vertical) / dot(c.vertical, c.vertical) * (ortho ? 1.0 : c.focal_length / ahead);
  const double j = sv * double(H - 1) + 0.5 * double(H - 1);  // from the bottom, as kernels/scalar.h
  if ((!ortho && !(ahead > 0.0)) || !(j == j)) return uint32_t(H);
  return uint32_t(H - 1 - std::clamp<int64_t>(std::llround(std::clamp(j, -1.0, double(H))), 0, H - 1));
}

std::pair<size_t, size_t> chunk(size_t n, size_t t, size_t chunks) { return {n * t / chunks, n * (t + 1) / chunks}; }

// A sphere's nearest distance |O - C| - r (negative inside), and the pixels its disc covers.
struct depth_of {
  double nearest, pixels;
  double lateral = 0.0;  // orthographic: max(|cx|, |cy|) + r, its reach off the view's axis
};
depth_of depth_of_sphere(const camera& c, const sphere& b) {
  const vec3 p = to_glm(b.center) - c.origin;
  const double dist = glm::length(p), ahead = -glm::dot(p, c.axis_w);
  const double all = double(c.image_width) * double(c.image_height);
  if (c.proj == projection::orthographic) {  // from the image plane, along the view; a disc of radius r
    const double rho = b.radius * double(c.image_height - 1) / c.viewport_height;
    const double lateral = std::max(std::abs(glm::dot(p, c.axis_u)), std::abs(glm::dot(p, c.axis_v))) + b.radius;
    return {ahead - b.radius, std::min(all, 3.14159 * rho * rho), lateral};
  }
  if (!(ahead > b.radius)) return {dist - b.radius, all};
  // The disc's radius on the image plane, in pixels: r / sqrt(ahead^2 - r^2) of the focal length.
  const double rho = b.radius / std::sqrt(ahead * ahead - b.radius * b.radius) * c.focal_length *
                     double(c.image_height - 1) / c.viewport_height;
  return {dist - b.radius, std::min(all, 3.14159 * rho * rho)};
}

// The spheres' shadings and nearest distances' range; each key's raw material where reordered.
struct survey {
  bool any_flat = false, any_normal = false, any_lit = false;
  bool one_look = true;  // every sphere shaded as the first is, in its colour
  double near_lo = INFINITY, near_hi = -INFINITY, lateral = 0.0;
};

bool same_look(const sphere& a, const sphere& b) {
  return a.shade == b.shade && (a.shade == shading::normal || a.color == b.color);
}
survey survey_spheres(const scene& s, sphere_order order, size_t team, uint32_t* key) {
  const bool ortho = s.cam.proj == projection::orthographic, depth = order == sphere_order::depth;
  const bool rows = order == sphere_order::rows;
  bool any_flat = false, any_normal = false, any_lit = false, one_look = true;
  double lo = INFINITY, hi = -INFINITY, lateral = 0.0;
  const size_t n = s.sphere_count();
  const sphere first = n > 0 ? s.sphere_at(0) : sphere{};
#pragma omp parallel for schedule(static, 1) num_threads(int(team)) \
    reduction(|| : any_flat, any_normal, any_lit) reduction(&& : one_look) reduction(min : lo) reduction(max : hi, lateral)
  for (size_t t = 0; t < team; ++t) {
    const auto [begin, end] = chunk(n, t, team);
    for (size_t k = begin; k < end; ++k) {
      const sphere b = s.sphere_at(k);  // a vector's, or a caller's arrays'
      one_look = one_look && same_look(first, b);
      any_flat = any_flat || b.shade == shading::flat;
      any_lit = any_lit || b.shade == shading::lit;
      any_normal = any_normal || b.shade == shading::normal;
      if (rows) key[k] = centre_row(s.cam, to_glm(b.center));
      if (!depth && !ortho) continue;
      const depth_of d = depth_of_sphere(s.cam, b);
      lo = std::min(lo, d.nearest);
      hi = std::max(hi, d.nearest);
      lateral = std::max(lateral, d.lateral);
      if (depth) key[k] = std::bit_cast<uint32_t>(float(d.nearest));
    }
  }
  return {any_flat, any_normal, any_lit, one_look, lo, hi, lateral};
}

// The spheres' screen discs added up, in images, estimated from at most 4096 of them.
double images_covered(const scene& s) {
  const size_t n = s.sphere_count(), step = std::max<size_t>(1, n / 4096);
  double pixels = 0.0;
  size_t seen = 0;
  for (size_t k = 0; k < n; k += step, ++seen) pixels += depth_of_sphere(s.cam, s.sphere_at(k)).pixels;
  return seen == 0 ? 0.0 : pixels * double(n) / double(seen) / (double(s.cam.image_width) * double(s.cam.image_height));
}

// Bucket b holds the nearest distances from lo + b step on; its key is at most that times
// (1 - 2^-15), rounded down, and for an orthographic camera (whose depths err more off its axis)
// lower by another 2^-10 of that reach.
struct depth_buckets {
  double lo, step;
  double offset = 0.0;  // subtracted from the keys: an orthographic camera's plane offset
  double slack = 0.0;   // subtracted too: 2^-10 of an orthographic scene's reach off the axis
  uint32_t of(float nearest) const {
    if (!(step > 0.0)) return 0;
    const double b = std::floor((double(nearest) - lo) / step);
    return uint32_t(std::clamp(b, 0.0, double(float_spheres::depth_buckets - 1)));
  }
  float key(size_t b) const {
    const double at = lo + double(b) * step - offset;
    const double k = at - 0x1p-15 * std::abs(at) - 0x1p-15 * step - slack;
    float f = float(k);
    if (double(f) > k) f = std::nextafter(f, -INFINITY);
    return f;
  }
};

// The counting sort's places: next[t * keys + key] is chunk t's next place for that key (stable).
std::vector<uint32_t> places(const uint32_t* key, size_t n, size_t keys, size_t team) {
  std::vector<uint32_t> next(team * keys, 0);
#pragma omp parallel for schedule(static, 1) num_threads(int(team))
  for (size_t t = 0; t < team; ++t) {
    const auto [begin, end] = chunk(n, t, team);
    for (size_t k = begin; k < end; ++k) ++next[t * keys + key[k]];
  }
  for (size_t r = 0, place = 0; r < keys; ++r)
    for (size_t t = 0; t < team; ++t) place += std::exchange(next[t * keys + r], uint32_t(place));
  return next;
}

void allocate(float_spheres& sp, size_t n, bool indexed, bool colored) {
  sp.rec.resize(n);
  if (indexed) sp.order.resize(n);
  if (colored)
    for (filled_array<float>* a : {&sp.red, &sp.green, &sp.blue, &sp.kind}) a->resize(n);
}

// A sphere's colour and kind as the kernels read them (a normal-shaded one's colour: 0).
struct sphere_look {
  float red, green, blue;
  float kind;  // a shading_kind
};
sphere_look look_of(const sphere& b) {
  const bool flat = b.shade == shading::flat, lit = b.shade == shading::lit;
  if (!flat && !lit) return {0.0f, 0.0f, 0.0f, shading_kind::normal};
  return {flush(b.color.x) + 0.0f, flush(b.color.y) + 0.0f, flush(b.color.z) + 0.0f,
          flat ? shading_kind::flat : shading_kind::lit};
}

void one_colour(float_spheres& sp, const sphere& b) {
  const sphere_look l = look_of(b);
  sp.red.assign(1, l.red);
  sp.green.assign(1, l.green);
  sp.blue.assign(1, l.blue);
  sp.kind.assign(1, l.kind);
}

// Sphere b's record, colour and kind at place i.
void write_sphere(float_spheres& sp, size_t i, const sphere& b, const float_scene& f, const camera& c, bool colored,
                  uint16_t depth) {
  sp.rec[i] = f.orthographic ? record_of_ortho(b, c, f.plane_offset) : record_of(b, c.origin);
  sp.rec[i].depth = depth;
  if (!colored) return;
  const sphere_look l = look_of(b);
  sp.red[i] = l.red;
  sp.green[i] = l.green;
  sp.blue[i] = l.blue;
  sp.kind[i] = l.kind;
}

struct placement {
  const uint32_t* key;
  std::vector<uint32_t>& next;
  size_t keys, team;
  bool reorder, indexed, colored;
};

// Writes every sphere's record (colour, index) in its place; whether a camera is inside a sphere.
// Spheres in arrays (a particle file's) are gathered: each place first gets its sphere's index,
// then places are filled front to back (a miss a column, not one per array a record spans).
bool fill_spheres(float_scene& f, const scene& s, const placement& p) {
  float_spheres& sp = f.spheres;
  const size_t n = s.sphere_count(), keys = p.keys;
  const camera& c = s.cam;
  const bool gather = p.reorder && s.arrays, depth = p.indexed;
  out_of_order_array<uint32_t> placed(gather && !p.indexed ? n : 0);  // written out of order
  uint32_t* perm = p.indexed ? sp.order.data() : placed.data();
  const auto depth_of = [&](size_t k) { return depth ? uint16_t(p.key[k]) : uint16_t(0); };
  bool any_inside = false;
#pragma omp parallel for schedule(static, 1) num_threads(int(p.team)) reduction(|| : any_inside)
  for (size_t t = 0; t < p.team; ++t) {
    const auto [begin, end] = chunk(n, t, p.team);
    for (size_t k = begin; k < end; ++k) {
      // The places of the spheres a few ahead are fetched early, so that their misses overlap.
      constexpr size_t ahead = 16;
      if (p.reorder && !gather && k + ahead < end) {
        const size_t later = p.next[t * keys + p.key[k + ahead]];
        __builtin_prefetch(&sp.rec[later], 1);
        if (p.indexed) __builtin_prefetch(&sp.order[later], 1);
        if (p.colored)
          for (const float* a : {sp.red.data(), sp.green.data(), sp.blue.data(), sp.kind.data()})
            __builtin_prefetch(a + later, 1);
      }
      const size_t i = p.reorder ? p.next[t * keys + p.key[k]]++ : k;
      if (gather) {
        perm[i] = uint32_t(k);
        continue;
      }
      write_sphere(sp, i, s.sphere_at(k), f, c, p.colored, depth_of(k));
      any_inside = any_inside || sp.rec[i].inside;
      if (p.indexed) sp.order[i] = uint32_t(k);
    }
  }
  if (!gather) return any_inside;
#pragma omp parallel for schedule(static, 1) num_threads(int(p.team)) reduction(|| : any_inside)
  for (size_t t = 0; t < p.team; ++t) {
    const auto [begin, end] = chunk(n, t, p.team);
    for (size_t i = begin; i < end; ++i) {
      const size_t k = perm[i];
      write_sphere(sp, i, s.sphere_at(k), f, c, p.colored, depth_of(k));
      any_inside = any_inside || sp.rec[i].inside;
    }
  }
  return any_inside;
}

}  // namespace

float_scene prepare_float_scene(const scene& s, int threads, size_t sort_from, sphere_order order) {
  const camera& c = s.cam;
  float_scene f;
  prepare_camera(f, s);

  // In parallel over chunks (the bytes do not depend on the threads); reordered by a counting sort.
  float_spheres& sp = f.spheres;
  const size_t n = s.sphere_count();
  if (order == sphere_order::automatic && n < sort_from) order = sphere_order::scene;
  const bool reorder = order != sphere_order::scene;
  // One chunk a thread, no more chunks than spheres per key (4 bytes a key a chunk).
  size_t team = n < (size_t(1) << 15) ? 1 : size_t(std::max(1, threads));
  if (order == sphere_order::automatic)
    order = images_covered(s) > (n < small_scene ? deep_from_small : deep_from) ? sphere_order::depth
                                                                               : sphere_order::rows;
  out_of_order_array<uint32_t> key(reorder ? n : 0);  // read out of order where gathered
  const survey v = survey_spheres(s, order, team, key.data());
  // Orthographic depths from the nearest sphere's front (if ahead): the scene's own precision.
  if (f.orthographic && n > 0) f.plane_offset = std::max(0.0, v.near_lo);
  const depth_buckets buckets{v.near_lo, (v.near_hi - v.near_lo) / double(float_spheres::depth_buckets),
                              f.plane_offset, 0x1p-10 * v.lateral};
  size_t keys = 1;
  if (order == sphere_order::rows) {
    keys = size_t(c.image_height) + 1;  // the rows 0 .. H (H: not ahead)
  } else if (order == sphere_order::depth) {
    keys = float_spheres::depth_buckets;
    for (size_t k = 0; k < n; ++k) key[k] = buckets.of(std::bit_cast<float>(key[k]));
    sp.depth_key.resize(keys);
    for (size_t b = 0; b < keys; ++b) sp.depth_key[b] = buckets.key(b);
  }
  if (reorder) team = std::clamp<size_t>(n / keys, 1, team);
  std::vector<uint32_t> next = reorder ? places(key.data(), n, keys, team) : std::vector<uint32_t>{};
  // Colours only where some sphere has one, one for all where every sphere has the same.
  const bool colored = (v.any_flat || v.any_lit) && !v.one_look;
  // Scene indices for the tie rule in depth order only (rows keep one key's spheres in order).
  const bool indexed = order == sphere_order::depth;
  allocate(sp, n, indexed, colored);
  sp.any_inside = fill_spheres(f, s, {key.data(), next, keys, team, reorder, indexed, colored});
  if ((v.any_flat || v.any_lit) && v.one_look) one_colour(sp, s.sphere_at(0));
  sp.any_flat = v.any_flat;
  sp.any_normal = v.any_normal;
  sp.any_lit = v.any_lit;
  sp.cull_radius.resize(n);
#pragma omp parallel for schedule(static) num_threads(team)
  for (size_t k = 0; k < n; ++k) sp.cull_radius[k] = cull_radius_of(sp.rec[k]);
  return f;
}

}  // namespace raycast
