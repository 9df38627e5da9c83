// The top of every per-target kernel source (sky_kernel.cpp,
// sphere_kernel.cpp): CMake compiles each once per target of
// simd/targets.h, with RAYCAST_ISA the target's name and
// RAYCAST_TARGET_HEADER its vector layer, which comes first.
#pragma once
#include RAYCAST_TARGET_HEADER

#include "kernels/kernel.h"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

using namespace raycast::simd::RAYCAST_ISA;
constexpr int N = vfloat::size;  // pixels a batch

}  // namespace
}  // namespace raycast::kernels::RAYCAST_ISA
