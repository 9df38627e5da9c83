// What this CPU and OS can run (CPUID, XGETBV, HWCAP): the only place that asks.
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

// Detected once; RAYCAST_MAX_ISA=<target> turns off the targets after it (cpu.cpp).
const cpu_features& cpu();

// The targets' names, in targets.h's order: what RAYCAST_MAX_ISA takes.
std::vector<std::string_view> target_names();
// RAYCAST_MAX_ISA's value where it is not a target's name (it caps nothing), else nothing.
std::optional<std::string> unknown_max_isa();

}  // namespace raycast
