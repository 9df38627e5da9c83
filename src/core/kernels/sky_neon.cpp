// The sky kernel for neon (AArch64, where NEON is always there: no extra
// flags). raycast_core's -ffp-contract=off keeps exact mode unfused.
#include "simd/neon.h"
#define RAYCAST_ISA neon

#include "sky_kernel.inl"
