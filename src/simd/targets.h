// The targets the kernels are compiled for, declared once. Everything else is
// derived from this list: CMake reads it for the targets to build and their
// compiler flags (src/simd/CMakeLists.txt reads the X(...) lines below), and
// the C++ side expands it for the kernels' declarations (kernels/kernel.h),
// the backends, their names and dispatch (render/backend.h), the values of
// RAYCAST_MAX_ISA (simd/cpu.cpp) and the tests' per-target lists.
//
// X(name, architecture, lanes, what the CPU needs, compiler flags), in the
// order `auto` prefers them least to most (it takes the last one this build
// has and this CPU runs):
//   name          the vector layer's header (simd/<name>.h) and namespace
//                 (raycast::simd::<name>, raycast::kernels::<name>), and the
//                 backend's name (--backend <name>)
//   architecture  where it is built: any, x86_64 or aarch64
//   lanes         pixels a batch
//   needs         what a CPU must have, as the refusal names it
//   flags         its translation units' compiler flags
// `scalar` is the 1-lane target: the float renderer one pixel at a time, the
// same kernel source at width 1, built everywhere.
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

// RAYCAST_ON_<architecture>(code...) keeps its code in builds for that
// architecture only, so a target's functions are named only where they exist.
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
