// What this CPU and OS can run: CPUID for the instructions, XGETBV for whether
// the OS saves the wide registers. The only place that asks.
#pragma once
#include <optional>
#include <string>

namespace raycast {

struct cpu_features {
  bool sse2 = false;
  bool avx2_fma = false;  // AVX2 + FMA, with the OS saving YMM state
  bool avx512 = false;    // AVX-512 F + BW + VL, with the OS saving ZMM and mask state
  bool neon = false;      // AArch64 Advanced SIMD (always there on AArch64)
};

// Detected once. The environment variable RAYCAST_MAX_ISA (scalar, sse2,
// avx2; scalar on AArch64) caps it, to run this machine as an older one would.
const cpu_features& cpu();

// Why RAYCAST_MAX_ISA's value is not one it knows, or nothing (unset, empty
// or valid). An unknown value caps nothing; the CLI refuses it.
std::optional<std::string> max_isa_error();

}  // namespace raycast
