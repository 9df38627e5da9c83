// ops.h's table for avx512, compiled with its flags (tests/CMakeLists.txt).
#include "simd/avx512.h"
#define RAYCAST_ISA avx512

#include "ops.inl"
