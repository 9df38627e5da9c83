#include "embree_peer.h"

#include <embree3/rtcore.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <chrono>
#include <vector>

#include "light/secondary.h"

namespace raycast::bench {
namespace {

// Embree reports through this instead of printing on our stderr; the first
// message is kept.
void keep_error(void* user, RTCError code, const char* str) {
  auto* msg = static_cast<std::string*>(user);
  if (msg->empty())
    *msg = "Embree error " + std::to_string(int(code)) + (str ? std::string(": ") + str : std::string());
}

// Embree's advice for speed: flush-to-zero and denormals-are-zero while it
// traces; the caller's MXCSR is restored afterwards.
class ftz_daz {
 public:
  ftz_daz() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040); }
  ~ftz_daz() { _mm_setcsr(saved_); }

 private:
  unsigned saved_;
};

struct float3 {
  float x, y, z;
};

// One lit hit of the Embree peer's frame: where its secondary rays start
// and what they found.
struct lit_hit {
  int64_t pixel;   // row-major index in the band
  unsigned prim;
  float p[3], n[3];  // P = C + r n_out; n facing the ray
  float tnear, diffuse;
  uint32_t open = 0;    // AO rays that met nothing
  bool shadowed = false;
};


}  // namespace

struct embree_peer::impl {
  const scene& s;
  int threads;
  std::string error;
  RTCDevice device = nullptr;
  RTCScene rtc_scene = nullptr;
  std::vector<float3> centers;
  std::vector<float3> flat;      // the flat colour, for flat-shaded spheres
  std::vector<char> is_flat, is_lit;
  std::vector<vec3> column;      // u_of(i) horizontal, per column: no division per pixel
  float3 origin{}, bottom{}, top{}, lo{}, hi{};

  impl(const scene& sc, int n) : s(sc), threads(n) {
    device = rtcNewDevice(("threads=" + std::to_string(threads) + ",verbose=0").c_str());
    if (!device) {
      error = "rtcNewDevice failed (Embree error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")";
      return;
    }
    rtcSetDeviceErrorFunction(device, keep_error, &error);
    rtc_scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(rtc_scene, RTC_BUILD_QUALITY_HIGH);
    if (!s.spheres.empty()) {
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), s.spheres.size()));
      if (v)
        for (size_t k = 0; k < s.spheres.size(); ++k) {
          const sphere& sp = s.spheres[k];
          v[4 * k + 0] = float(sp.center.x);
          v[4 * k + 1] = float(sp.center.y);
          v[4 * k + 2] = float(sp.center.z);
          v[4 * k + 3] = float(sp.radius);
        }
      rtcCommitGeometry(g);
      rtcAttachGeometry(rtc_scene, g);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(rtc_scene);
    for (const sphere& sp : s.spheres) {
      centers.push_back({float(sp.center.x), float(sp.center.y), float(sp.center.z)});
      flat.push_back({float(sp.color.x), float(sp.color.y), float(sp.color.z)});
      is_flat.push_back(sp.shade == shading::flat);
      is_lit.push_back(sp.shade == shading::lit);
    }
    const camera& cam = s.cam;
    column.resize(size_t(cam.image_width));
    for (int64_t i = 0; i < cam.image_width; ++i) column[size_t(i)] = cam.u_of(i) * cam.horizontal;
    origin = {float(cam.origin.x), float(cam.origin.y), float(cam.origin.z)};
    bottom = {float(s.sky.bottom.r), float(s.sky.bottom.g), float(s.sky.bottom.b)};
    top = {float(s.sky.top.r), float(s.sky.top.g), float(s.sky.top.b)};
    lo = {std::min(bottom.x, top.x), std::min(bottom.y, top.y), std::min(bottom.z, top.z)};
    hi = {std::max(bottom.x, top.x), std::max(bottom.y, top.y), std::max(bottom.z, top.z)};
  }

  ~impl() {
    if (rtc_scene) rtcReleaseScene(rtc_scene);
    if (device) rtcReleaseDevice(device);
  }

  // The ray direction of pixel (i, row j from the bottom), formed in double
  // from the camera and rounded to float once, as an Embree user with our
  // camera would hand it over.
  // The ray's direction in float, scaled by a power of two to a largest
  // component in [0.5, 1) (a ray is its direction: Embree refuses components
  // beyond about 1.8e18, and a far viewport's would overflow float).
  float3 direction(const vec3& row_base, int64_t i) const {
    const vec3 d = row_base + column[size_t(i)];
    int e = 0;
    std::frexp(std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}), &e);
    const vec3 u = d * std::ldexp(1.0, -e);
    return {float(u.x), float(u.y), float(u.z)};
  }

  // The colour of a ray that hit sphere prim at distance t with Embree's
  // geometric normal ng (unnormalized), or missed (prim = invalid).
  float3 shade(const float3& d, unsigned geom, unsigned prim, const float3& ng) const {
    if (geom == RTC_INVALID_GEOMETRY_ID) {
      // The sky, in float: t = 0.5 (unit.y + 1), the lerp clamped between the colours.
      const float len = std::sqrt(std::max((d.x * d.x + d.y * d.y) + d.z * d.z,
                                           std::numeric_limits<float>::min()));
      const float t = (d.y / len + 1.0f) * 0.5f;
      return {std::clamp(bottom.x + t * (top.x - bottom.x), lo.x, hi.x),
              std::clamp(bottom.y + t * (top.y - bottom.y), lo.y, hi.y),
              std::clamp(bottom.z + t * (top.z - bottom.z), lo.z, hi.z)};
    }
    if (is_flat[prim]) return flat[prim];
    const float len = std::sqrt((ng.x * ng.x + ng.y * ng.y) + ng.z * ng.z);
    float sgn = 1.0f / len;
    // Face the ray as the book's set_face_normal does: front face only where d.N < 0.
    if (!((d.x * ng.x + d.y * ng.y) + d.z * ng.z < 0.0f)) sgn = -sgn;
    const float3 n{ng.x * sgn, ng.y * sgn, ng.z * sgn};
    if (is_lit[prim]) {  // scene/sphere.h's headlight
      const float facing = -((n.x * d.x + n.y * d.y) + n.z * d.z) / std::sqrt((d.x * d.x + d.y * d.y) + d.z * d.z);
      const float light = lit_ambient + lit_diffuse * std::max(facing, 0.0f);
      return {flat[prim].x * light, flat[prim].y * light, flat[prim].z * light};
    }
    return {(n.x + 1.0f) * 0.5f, (n.y + 1.0f) * 0.5f, (n.z + 1.0f) * 0.5f};
  }

  static void store(const image_band& band, unsigned char* row, int64_t i, const float3& c) {
    if (band.format == pixel_format::rgb8) {
      row[3 * i + 0] = static_cast<unsigned char>(int(std::clamp(c.x, 0.0f, 1.0f) * 255.999f));
      row[3 * i + 1] = static_cast<unsigned char>(int(std::clamp(c.y, 0.0f, 1.0f) * 255.999f));
      row[3 * i + 2] = static_cast<unsigned char>(int(std::clamp(c.z, 0.0f, 1.0f) * 255.999f));
    } else {
      const float f[3] = {c.x, c.y, c.z};
      std::memcpy(row + 12 * i, f, sizeof f);
    }
  }

  void render16(const image_band& band) const {
    const camera& cam = s.cam;
    const int64_t W = cam.image_width, H = cam.image_height;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // primary rays: Embree's fast path
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    float3 dir[16];
    for (int64_t r = band.row_begin; r < band.row_end; ++r) {
      const vec3 base = cam.corner_dir + cam.v_of(H - 1 - r) * cam.vertical;
      unsigned char* row = band.row(r);
      for (int64_t i0 = 0; i0 < W; i0 += 16) {
        const int n = int(std::min<int64_t>(16, W - i0));
        for (int k = 0; k < 16; ++k) {
          valid[k] = k < n ? -1 : 0;
          float3 from = origin;
          if (cam.proj == projection::orthographic) {  // scene/camera.h: from the image plane, along -w
            const ray along = cam.get_ray(cam.u_of(std::min(i0 + k, W - 1)), cam.v_of(H - 1 - r));
            from = {float(along.origin().x), float(along.origin().y), float(along.origin().z)};
            dir[k] = {float(along.direction().x), float(along.direction().y), float(along.direction().z)};
          } else {
            dir[k] = direction(base, std::min(i0 + k, W - 1));
          }
          rh.ray.org_x[k] = from.x;
          rh.ray.org_y[k] = from.y;
          rh.ray.org_z[k] = from.z;
          rh.ray.dir_x[k] = dir[k].x;
          rh.ray.dir_y[k] = dir[k].y;
          rh.ray.dir_z[k] = dir[k].z;
          rh.ray.tnear[k] = 0.0f;
          rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
          rh.ray.time[k] = 0.0f;
          rh.ray.mask[k] = ~0u;
          rh.ray.id[k] = 0;
          rh.ray.flags[k] = 0;
          rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, rtc_scene, &ctx, &rh);
        for (int k = 0; k < n; ++k)
          store(band, row, i0 + k,
                shade(dir[k], rh.hit.geomID[k], rh.hit.primID[k],
                      {rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]}));
      }
    }
  }

  // The lit hits of the band's primary rays (perspective), traced again
  // with rtcIntersect16 as render16 traces them.
  std::vector<lit_hit> lit_hits(const image_band& band) const {
    const camera& cam = s.cam;
    const int64_t W = cam.image_width, H = cam.image_height;
    std::vector<lit_hit> hits;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    const ftz_daz guard;
    for (int64_t r = band.row_begin; r < band.row_end; ++r) {
      const vec3 base = cam.corner_dir + cam.v_of(H - 1 - r) * cam.vertical;
      for (int64_t i0 = 0; i0 < W; i0 += 16) {
        float3 dir[16];
        for (int k = 0; k < 16; ++k) {
          valid[k] = i0 + k < W ? -1 : 0;
          dir[k] = direction(base, std::min(i0 + k, W - 1));
          rh.ray.org_x[k] = origin.x, rh.ray.org_y[k] = origin.y, rh.ray.org_z[k] = origin.z;
          rh.ray.dir_x[k] = dir[k].x, rh.ray.dir_y[k] = dir[k].y, rh.ray.dir_z[k] = dir[k].z;
          rh.ray.tnear[k] = 0.0f, rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
          rh.ray.time[k] = 0.0f, rh.ray.mask[k] = ~0u, rh.ray.id[k] = 0, rh.ray.flags[k] = 0;
          rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, rtc_scene, &ctx, &rh);
        for (int k = 0; k < 16 && i0 + k < W; ++k)
          if (rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID && is_lit[rh.hit.primID[k]])
            hits.push_back(lit_of((r - band.row_begin) * W + i0 + k, rh.hit.primID[k], dir[k],
                                  {rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]}));
      }
    }
    return hits;
  }

  lit_hit lit_of(int64_t pixel, unsigned prim, const float3& d, const float3& ng) const {
    lit_hit h{};
    h.pixel = pixel;
    h.prim = prim;
    const float inv = 1.0f / std::sqrt((ng.x * ng.x + ng.y * ng.y) + ng.z * ng.z);
    const float out[3] = {ng.x * inv, ng.y * inv, ng.z * inv};
    const bool front = (d.x * ng.x + d.y * ng.y) + d.z * ng.z < 0.0f;
    const sphere& sp = s.spheres[prim];
    const float r = float(sp.radius);
    for (int c = 0; c < 3; ++c) {
      h.n[c] = front ? out[c] : -out[c];
      h.p[c] = float(sp.center[c]) + r * out[c];
    }
    h.tnear = r * 0x1p-10f;
    if (s.light.direction) {
      const vec3 l = unit_vector(to_glm(*s.light.direction));
      h.diffuse = std::max((h.n[0] * float(l.x) + h.n[1] * float(l.y)) + h.n[2] * float(l.z), 0.0f);
    } else {
      const float len = std::sqrt((d.x * d.x + d.y * d.y) + d.z * d.z);
      h.diffuse = std::max(-((h.n[0] * d.x + h.n[1] * d.y) + h.n[2] * d.z) / len, 0.0f);
    }
    return h;
  }

  // One ray from the camera origin along d, rtcIntersect1.
  RTCRayHit intersect1(const float3& d) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = origin.x;
    rh.ray.org_y = origin.y;
    rh.ray.org_z = origin.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.time = 0.0f;
    rh.ray.mask = ~0u;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rtc_scene, &ctx, &rh);
    return rh;
  }

  void render1(const image_band& band) const {
    const camera& cam = s.cam;
    const int64_t W = cam.image_width, H = cam.image_height;
    for (int64_t r = band.row_begin; r < band.row_end; ++r) {
      const vec3 base = cam.corner_dir + cam.v_of(H - 1 - r) * cam.vertical;
      unsigned char* row = band.row(r);
      for (int64_t i = 0; i < W; ++i) {
        const float3 d = direction(base, i);
        const RTCRayHit rh = intersect1(d);
        store(band, row, i, shade(d, rh.hit.geomID, rh.hit.primID, {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z}));
      }
    }
  }

  hit trace(int64_t i, int64_t j) const {
    const float3 d = direction(s.cam.corner_dir + s.cam.v_of(j) * s.cam.vertical, i);
    const RTCRayHit rh = intersect1(d);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
    const double len = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
    return {int64_t(rh.hit.primID), double(rh.ray.tfar) * len};
  }
};

namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Casts count rays with rtcOccluded16, ray k from make(k, org, dir, tnear,
// tfar) and reports each verdict to done(k, occluded); in parallel packets.
template <class Make, class Done>
void occluded16(RTCScene scene, int threads, bool coherent, int64_t count, Make make, Done done) {
  const int64_t packets = (count + 15) / 16;
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads) if (threads > 1)
  for (int64_t q = 0; q < packets; ++q) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    alignas(64) RTCRay16 ray;
    alignas(64) int valid[16];
    for (int l = 0; l < 16; ++l) {
      const int64_t k = q * 16 + l;
      valid[l] = k < count ? -1 : 0;
      float o[3] = {0, 0, 0}, d[3] = {0, 0, 1}, tnear = 0, tfar = 0;
      if (k < count) make(k, o, d, tnear, tfar);
      ray.org_x[l] = o[0], ray.org_y[l] = o[1], ray.org_z[l] = o[2];
      ray.dir_x[l] = d[0], ray.dir_y[l] = d[1], ray.dir_z[l] = d[2];
      ray.tnear[l] = tnear, ray.tfar[l] = tfar, ray.time[l] = 0, ray.mask[l] = ~0u, ray.id[l] = 0, ray.flags[l] = 0;
    }
    const ftz_daz guard;
    rtcOccluded16(valid, scene, &ctx, &ray);
    for (int l = 0; l < 16 && q * 16 + l < count; ++l) done(q * 16 + l, ray.tfar[l] < 0.0f);
  }
}

}  // namespace

embree_peer::light_seconds embree_peer::render_lit(const image_band& band, const sampling::ao_plan& ao) const {
  light_seconds sec;
  if (!impl_->error.empty()) return sec;
  const impl& m = *impl_;
  const scene& s = m.s;
  const int64_t W = s.cam.image_width, H = s.cam.image_height;
  auto t0 = std::chrono::steady_clock::now();
  render(band, mode::packet16);  // every pixel as the primary frame shades it; lit ones are redone below
  sec.primary = since(t0);
  // The lit hits, traced again (not timed: the peer's primary cost is the frame's above).
  std::vector<lit_hit> hits = m.lit_hits(band);
  const float inf = std::numeric_limits<float>::infinity();
  const vec3 l = s.light.direction ? unit_vector(to_glm(*s.light.direction)) : vec3(0, 0, 1);
  const float light[3] = {float(l.x), float(l.y), float(l.z)};
  t0 = std::chrono::steady_clock::now();
  if (s.light.shadows) {
    std::vector<int64_t> lit;
    for (int64_t k = 0; k < int64_t(hits.size()); ++k)
      if (hits[size_t(k)].diffuse > 0.0f) lit.push_back(k);
    occluded16(
        m.rtc_scene, m.threads, true, int64_t(lit.size()),
        [&](int64_t k, float o[3], float d[3], float& tn, float& tf) {
          const lit_hit& h = hits[size_t(lit[size_t(k)])];
          for (int c = 0; c < 3; ++c) o[c] = h.p[c], d[c] = light[c];
          tn = h.tnear, tf = inf;
        },
        [&](int64_t k, bool occ) { hits[size_t(lit[size_t(k)])].shadowed = occ; });
  }
  sec.shadow = since(t0);
  t0 = std::chrono::steady_clock::now();
  const int64_t per = ao.count, rays = int64_t(hits.size()) * per;
  const float distance = float(s.light.ao_distance);
  occluded16(
      m.rtc_scene, m.threads, false, rays,
      [&](int64_t k, float o[3], float d[3], float& tn, float& tf) {
        const lit_hit& h = hits[size_t(k / per)];
        float u1, u2;
        sampling::ao_numbers(ao, uint32_t(h.pixel % W), uint32_t(H - 1 - (band.row_begin + h.pixel / W)), 0,
                             uint32_t(k % per), u1, u2);
        ao_direction(h.n, u1, u2, d);
        for (int c = 0; c < 3; ++c) o[c] = h.p[c];
        tn = h.tnear, tf = distance;
      },
      [&](int64_t k, bool occ) {
        if (!occ) __atomic_fetch_add(&hits[size_t(k / per)].open, 1u, __ATOMIC_RELAXED);
      });
  sec.ao = since(t0);
  for (const lit_hit& h : hits) {
    const float a = per > 0 ? float(h.open) / float(per) : 1.0f;
    const float f = lit_ambient * a + (lit_diffuse * h.diffuse) * (h.shadowed ? 0.0f : 1.0f);
    const float3& c = m.flat[h.prim];
    impl::store(band, band.row(band.row_begin + h.pixel / W), h.pixel % W, {c.x * f, c.y * f, c.z * f});
  }
  return sec;
}

embree_peer::embree_peer(const scene& s, int threads) : impl_(std::make_unique<impl>(s, threads)) {}
embree_peer::~embree_peer() = default;
const std::string& embree_peer::error() const { return impl_->error; }

void embree_peer::render(const image_band& band, mode m) const {
  if (!impl_->error.empty()) return;
  const int64_t parts = (band.row_end - band.row_begin + 15) / 16;
#pragma omp parallel for schedule(dynamic, 1) num_threads(impl_->threads) if (impl_->threads > 1)
  for (int64_t k = 0; k < parts; ++k) {
    image_band part = band;
    part.row_begin = band.row_begin + 16 * k;
    part.row_end = std::min(band.row_end, part.row_begin + 16);
    part.data = band.row(part.row_begin);
    const ftz_daz guard;  // each thread has its own MXCSR
    if (m == mode::packet16) impl_->render16(part);
    else impl_->render1(part);
  }
}

embree_peer::hit embree_peer::trace(int64_t i, int64_t j) const {
  if (!impl_->error.empty()) return {};
  const ftz_daz guard;
  return impl_->trace(i, j);
}

}  // namespace raycast::bench
