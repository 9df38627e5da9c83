// The targets the kernels are compiled for, declared once: CMake reads the X(...) lines below
// (simd/CMakeLists.txt) and the C++ side expands them (README.md).
// X(name, architecture, lanes, what the CPU needs, compiler flags), in the order `auto` prefers
// them least to most (it takes the last one this build has and this CPU runs):
//   name          the header simd/<name>.h, the namespaces and the backend's name
//   architecture  where it is built: any, x86_64 or aarch64
//   lanes         pixels a batch
//   needs         what a CPU must have, as the refusal names it
//   flags         its translation units' compiler flags
#pragma once

// clang-format off
#define RAYCAST_TARGETS(X)                                                                          \
  X(scalar, any,      1, "",                    "")                                                 \
  X(sse2,   x86_64,   8, "SSE2",                "-msse2")                                           \
  X(avx2,   x86_64,   8, "AVX2 + FMA",          "-mavx2 -mfma")                                     \
  X(avx512, x86_64,  16, "AVX-512 F + BW + VL", "-mavx512f -mavx512bw -mavx512vl -mavx2 -mfma")     \
  X(neon,   aarch64,  8, "NEON",                "")
// clang-format on

// How messages name the architectures.
#define RAYCAST_ARCH_NAME_any "any"
#define RAYCAST_ARCH_NAME_x86_64 "x86-64"
#define RAYCAST_ARCH_NAME_aarch64 "AArch64"

// RAYCAST_ON_<architecture>(code...) keeps its code in builds for that architecture only.
#define RAYCAST_ON_any(...) __VA_ARGS__
#if defined(__x86_64__)
#define RAYCAST_ON_x86_64(...) __VA_ARGS__
#else
#define RAYCAST_ON_x86_64(...)
#endif
#if defined(__aarch64__)
#define RAYCAST_ON_aarch64(...) __VA_ARGS__
#else
#define RAYCAST_ON_aarch64(...)
#endif
