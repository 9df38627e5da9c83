#include "reference/reference.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

#include "reference/hittable.h"

namespace raycast {
namespace {

// Rounds to float; below the smallest normal float, 0 (so FTZ cannot change the output).
float to_float(double c) { return std::abs(c) < double(FLT_MIN) ? 0.0f : float(c); }

// Which pixel and sample a ray is, and ambient occlusion's plan.
struct ray_at {
  const sampling::ao_plan& ao;
  uint32_t i, j, sample;
};

// The light of a lit hit in double: every sphere asked, AO's numbers as the float renderers'.
double lit_light(const scene& s, const ray& r, const hit_record& rec, const ray_at& at) {
  const api::light& li = s.light;
  const vec3& n = rec.normal;  // facing the ray
  const vec3 l = li.direction ? unit_vector(to_glm(*li.direction)) : -glm::normalize(r.direction());
  const double diffuse = std::max(glm::dot(n, l), 0.0);
  // A hit seen from outside its sphere skips it (light/secondary.h).
  const sphere* skip = rec.front_face ? rec.object : nullptr;
  double shadow = 1.0, ambient = 1.0;
  if (li.shadows && diffuse > 0.0 && blocked(s.spheres, rec.p, l, INFINITY, skip)) shadow = 0.0;
  if (li.ao_samples > 0) {
    uint32_t open = 0;
    for (uint32_t k = 0; k < li.ao_samples; ++k) {
      float u1 = 0.0f, u2 = 0.0f;
      sampling::ao_numbers(at.ao, at.i, at.j, at.sample, k, u1, u2);
      if (!blocked(s.spheres, rec.p, cosine_direction(n, u1, u2), li.ao_distance, skip)) ++open;
    }
    ambient = double(open) / double(li.ao_samples);
  }
  return double(lit_ambient) * ambient + double(lit_diffuse) * diffuse * shadow;
}

color trace(const scene& s, const ray& r, const ray_at& at) {
  if (s.spheres.empty()) return ray_color(r, s.sky);
  hit_record rec;
  if (!hit_world(s.spheres, r, 0.0, INFINITY, rec)) return ray_color(r, s.sky);
  const color c = to_glm(rec.object->color);
  if (rec.object->shade == shading::flat) return c;
  if (rec.object->shade == shading::lit) {
    if (s.light.any()) return c * lit_light(s, r, rec, at);
    // scene/sphere.h's headlight
    const double facing = -glm::dot(rec.normal, glm::normalize(r.direction()));
    return c * (double(lit_ambient) + double(lit_diffuse) * std::max(facing, 0.0));
  }
  return 0.5 * (rec.normal + color(1.0, 1.0, 1.0));
}

// The plan the caller gave, or the default sampler's with seed 0.
sampling::ao_plan ao_plan_of(const scene& s, const sampling::ao_plan* ao) {
  return ao ? *ao : sampling::make_ao_plan(default_sampler, s.light.ao_samples, 0);
}

}  // namespace

color reference_pixel(const scene& s, int64_t i, int64_t j, const sampling::ao_plan* ao) {
  const camera& cam = s.cam;
  const sampling::ao_plan plan = ao_plan_of(s, ao);
  return trace(s, cam.get_ray(cam.u_of(i), cam.v_of(j)), {plan, uint32_t(i), uint32_t(j), 0});
}

color reference_pixel_samples(const scene& s, const sampling::sample_plan& plan, int64_t i, int64_t j,
                              const sampling::ao_plan* ao) {
  const camera& cam = s.cam;
  const sampling::ao_plan aop = ao_plan_of(s, ao);
  color sum(0.0);
  for (uint32_t k = 0; k < plan.count; ++k) {
    float xi = 0.0f, eta = 0.0f;
    sampling::sample_offsets(plan, uint32_t(i), uint32_t(j), k, xi, eta);
    const double u = cam.image_width == 1 ? 0.5 : (double(i) + xi) / double(cam.image_width - 1);
    const double v = cam.image_height == 1 ? 0.5 : (double(j) + eta) / double(cam.image_height - 1);
    sum += trace(s, cam.get_ray(u, v), {aop, uint32_t(i), uint32_t(j), k});
  }
  return sum / double(plan.count);
}

void render_reference(const scene& s, const image_band& band, const sampling::sample_plan* samples,
                      const sampling::ao_plan* ao) {
  const int64_t W = s.cam.image_width, H = s.cam.image_height;
  for (int64_t r = band.row_begin; r < band.row_end; ++r) {
    const int64_t j = H - 1 - r;
    for (int64_t i = band.col_begin; i < band.cols_end(W); ++i) {
      const color c = samples ? reference_pixel_samples(s, *samples, i, j, ao) : reference_pixel(s, i, j, ao);
      unsigned char* px = band.pixel(r, i);
      if (band.format == pixel_format::rgb8) {
        px[0] = to_byte(c.r), px[1] = to_byte(c.g), px[2] = to_byte(c.b);
      } else {
        const float f[3] = {to_float(c.r), to_float(c.g), to_float(c.b)};
        std::memcpy(px, f, sizeof f);
      }
    }
  }
}

}  // namespace raycast
