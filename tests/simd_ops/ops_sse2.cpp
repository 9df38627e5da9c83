// ops.h's table for sse2, compiled with its flags (tests/CMakeLists.txt).
#include "simd/sse2.h"
#define RAYCAST_ISA sse2

#include "ops.inl"
