// The spheres as the float renderers see them, and the order in which every
// float renderer (kernels/scalar.cpp, kernels/sphere_kernel.inl) intersects
// and shades them. Exact mode is this order on every backend, bit for bit.
//
// All primary rays start at the camera origin O, so everything that depends on
// O and a sphere only is a per-sphere constant, computed once in double and
// rounded to float once (prepare_float_scene):
//   f = O - C,   c = |f|^2 - r^2,   r2 = r^2,   inv_r = 1 / r
//
// Per pixel, with the camera direction d of kernels/scalar.h (scaled, not unit)
// and n2 = (d.x d.x + d.y d.y) + d.z d.z:
//   len = sqrt(max(n2, FLT_MIN));  u = (d.x / len, d.y / len, d.z / len)
//   (u.y is the sky's uy bit for bit: a ray that hits nothing gets the sky
//   colour of kernels/scalar.h's exact mode.)
// Per sphere, in scene order, with closest = FLT_MAX at the start:
//   b    = (f.x u.x + f.y u.y) + f.z u.z
//   v    = (f.x - b u.x, f.y - b u.y, f.z - b u.z)          the chord's midpoint - C
//   disc = r2 - ((v.x v.x + v.y v.y) + v.z v.z)              Hearn & Baker: r^2 - |f - (f.u)u|^2
//   s    = sqrt(max(disc, 0))
//   q    = -(b + copysign(s, b))                             Press et al.: no cancellation
//   t0   = c / q,  t1 = q                                    the two roots, t0 t1 = c
//   t    = t0 >= 0 ? t0 : t1                                 the nearest root that is not behind
//   hit  when disc >= 0 and t >= 0 and t <= closest; then closest = t
//        (t <= closest: on a tie the later sphere wins, as in the book's
//        hittable_list; closest starts at FLT_MAX, so no infinite or NaN t hits)
// Shading of the closest hit, per channel k:
//   flat:   the sphere's colour
//   normal: n_k = (f_k + t u_k) inv_r                       the outward normal
//           n = -n where (n_0 u_0 + n_1 u_1) + n_2 u_2 >= 0  the book's set_face_normal:
//                                                          it faces the ray (inside a sphere too)
//           colour_k = (n_k + 1) 0.5
// 8-bit: int(clamp(colour, 0, 1) * 255.999f), as the sky.
//
// Why this form: the textbook b^2 - c loses everything to cancellation for a
// small sphere far away (Ray Tracing Gems ch. 7: a unit sphere 4100 units away
// renders as a solid square); r^2 - |f - (f.u)u|^2 has an error relative to
// r^2, not to |f|^2. q never cancels, and t0 = c / q takes the near root from
// the product of the roots rather than from -b - s, which cancels when the
// camera is near the surface. c in double is exact to one rounding.
//
// Precision `fast` renders spheres exactly as `exact` does (no estimate is
// used yet); only the sky-only scene has a separate fast path.
//
// Every operation is a single IEEE operation; the kernels are compiled with
// -ffp-contract=off, so no fused multiply-add changes a rounding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace raycast {

// A structure of arrays, one entry per sphere in scene order.
struct float_spheres {
  std::vector<float> fx, fy, fz;  // f = O - C
  std::vector<float> c;           // |f|^2 - r^2
  std::vector<float> r2;          // r^2
  std::vector<float> inv_r;       // 1 / r
  std::vector<float> red, green, blue;  // flat colour (0 for normal-shaded spheres)
  std::vector<float> flat;        // 1 for flat-shaded spheres, 0 for normal-shaded
  bool any_flat = false, any_normal = false;

  size_t size() const { return fx.size(); }
  bool empty() const { return fx.empty(); }
};

// The same arrays as plain pointers, for the kernels: they are compiled per
// instruction set and must instantiate no standard-library template (an
// inline function built for AVX-512 could be picked by the linker for the
// others). The plan (render/plan.cpp) fills it.
struct sphere_arrays {
  const float *fx = nullptr, *fy = nullptr, *fz = nullptr, *c = nullptr, *r2 = nullptr,
              *inv_r = nullptr;
  const float *red = nullptr, *green = nullptr, *blue = nullptr, *flat = nullptr;
  size_t n = 0;
  bool any_flat = false, any_normal = false;
};

inline sphere_arrays arrays_of(const float_spheres& s) {
  return {s.fx.data(), s.fy.data(), s.fz.data(), s.c.data(), s.r2.data(), s.inv_r.data(),
          s.red.data(), s.green.data(), s.blue.data(), s.flat.data(), s.size(), s.any_flat, s.any_normal};
}

}  // namespace raycast
