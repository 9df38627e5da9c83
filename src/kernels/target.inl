// The top of every per-target kernel source (RAYCAST_ISA, RAYCAST_TARGET_HEADER: set by CMake).
#pragma once
#include RAYCAST_TARGET_HEADER

#include "kernels/kernel.h"

namespace raycast::kernels::RAYCAST_ISA {
namespace {

using namespace raycast::simd::RAYCAST_ISA;
constexpr int N = vfloat::size;  // pixels a batch

}  // namespace
}  // namespace raycast::kernels::RAYCAST_ISA
