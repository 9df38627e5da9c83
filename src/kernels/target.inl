// The top of every per-target kernel source: CMake compiles each once per target of
// simd/targets.h, with RAYCAST_ISA the target's name and RAYCAST_TARGET_HEADER its vector layer.
#pragma once
#include RAYCAST_TARGET_HEADER

#include "kernels/kernel.h"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

using namespace raycast::simd::RAYCAST_ISA;
constexpr int N = vfloat::size;  // pixels a batch

}  // namespace
}  // namespace raycast::kernels::RAYCAST_ISA
