// ops.h's table for avx2, compiled with its flags (tests/CMakeLists.txt).
#include "simd/avx2.h"
#define RAYCAST_ISA avx2

#include "ops.inl"
