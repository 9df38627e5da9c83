// The light's kernels (light/kernels.h) for one width: compiled once for the
// build's baseline and, on x86-64, again with -mavx2 (RAYCAST_LIGHT_LANES=8)
// and with AVX-512 (16). Everything here but the table's function is in the
// width's namespace and has internal linkage, so no copy of it can stand in
// for another width's (Build.TargetObjectsShareNoWeakSymbols); it calls no
// std:: function for the same reason.
#include <cstdint>

#include "light/far/bvh.h"
#include "light/kernels.h"
#include "light/lanes.h"

namespace raycast {
namespace lanes {
inline namespace RAYCAST_LANES_NAMESPACE {
namespace {

#include "light/far/occlude.inl"
#include "light/far/walk_group.inl"
#include "light/far/one_origin.inl"
#include "light/far/gather.inl"
#include "light/near/list_rays.inl"

light_kernels table() {
  light_kernels k;
  k.width = width;
  k.far_occluded = far_occluded;
  k.far_occluded_many = far_occluded_many;
  k.far_occluded_one_origin = far_occluded_one_origin;
  k.gather_ball = gather_ball;
  k.gather_capsule = gather_capsule;
  k.list_blocks = list_blocks;
  k.list_ao = list_ao;
  return k;
}

}  // namespace
}  // inline namespace RAYCAST_LANES_NAMESPACE
}  // namespace lanes

#if RAYCAST_LANES_WIDTH == 4
light_kernels kernels_w4() { return lanes::table(); }
#elif RAYCAST_LANES_WIDTH == 8
light_kernels kernels_w8() { return lanes::table(); }
#else
light_kernels kernels_w16() { return lanes::table(); }
#endif

}  // namespace raycast
