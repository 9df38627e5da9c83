// The sky kernel for avx512; compiled with that instruction set's flags (CMakeLists.txt).
#include "simd/avx512.h"
#define RAYCAST_ISA avx512

#include "kernels/sky_kernel.inl"
