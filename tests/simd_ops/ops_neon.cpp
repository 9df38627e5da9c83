// ops.h's table for neon (AArch64: no extra flags).
#include "simd/neon.h"
#define RAYCAST_ISA neon

#include "ops.inl"
