// The sky kernel for neon (AArch64, where NEON is always there: no extra
// flags). the kernels room's -ffp-contract=off keeps exact mode unfused.
#include "simd/neon.h"
#define RAYCAST_ISA neon

#include "kernels/sky_kernel.inl"
