// The sky kernel for avx2; compiled with that instruction set's flags (CMakeLists.txt).
#include "simd/avx2.h"
#define RAYCAST_ISA avx2

#include "kernels/sky_kernel.inl"
