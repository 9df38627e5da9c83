// What this CPU and OS can run: CPUID for the instructions, XGETBV for whether
// the OS saves the wide registers. The only place that asks.
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace raycast {

// One flag per target of simd/targets.h, named as the target.
struct cpu_features {
  bool scalar = true;   // the 1-lane target: every CPU
  bool sse2 = false;
  bool avx2 = false;    // AVX2 + FMA, with the OS saving YMM state
  bool avx512 = false;  // AVX-512 F + BW + VL, with the OS saving ZMM and mask state
  bool neon = false;    // AArch64 Advanced SIMD (always there on AArch64)
};

// Detected once. The environment variable RAYCAST_MAX_ISA (a target's name)
// caps it, to run this machine as an older one would: the targets after it
// in targets.h's list, of its architecture, are off (scalar: every vector one).
const cpu_features& cpu();

// The targets' names, in targets.h's order: what RAYCAST_MAX_ISA takes.
std::vector<std::string_view> target_names();
// RAYCAST_MAX_ISA's value where it is not a target's name, or nothing (unset,
// empty or valid). An unknown value caps nothing; the CLI refuses it.
std::optional<std::string> unknown_max_isa();

}  // namespace raycast
