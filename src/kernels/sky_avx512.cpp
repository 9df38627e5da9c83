// The sky kernel for avx512; compiled with that instruction set's flags (CMakeLists.txt).
#include "simd/avx512.h"
#define RAYCAST_ISA avx512
#define RAYCAST_HAS_MASKED_BYTE_STORE 1
#define RAYCAST_HAS_STORE4 1
#include "kernels/sky_kernel.inl"
