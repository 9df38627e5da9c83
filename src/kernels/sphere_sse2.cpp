// The sphere kernel for sse2; compiled with that instruction set's flags (CMakeLists.txt).
#include "simd/sse2.h"
#define RAYCAST_ISA sse2

#include "kernels/sphere_kernel.inl"
