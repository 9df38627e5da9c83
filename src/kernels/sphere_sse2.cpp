// The sphere kernel for sse2; compiled with that instruction set's flags (CMakeLists.txt).
#include "simd/sse2.h"
#define RAYCAST_ISA sse2
#define RAYCAST_SAMPLES_PER_PASS 1  // sphere_kernel.inl: two passes do not fit 16 xmm registers

#include "kernels/sphere_kernel.inl"
