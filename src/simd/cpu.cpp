#include "simd/cpu.h"

#include "simd/targets.h"

#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#include <cstdint>
#elif defined(__aarch64__)
#include <asm/hwcap.h>
#include <sys/auxv.h>
#endif

namespace raycast {
namespace {

#if defined(__x86_64__) || defined(__i386__)
uint64_t xgetbv0() {
  uint32_t lo = 0, hi = 0;
  __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
  return (uint64_t{hi} << 32) | lo;
}

cpu_features detect() {
  cpu_features f;
  unsigned a = 0, b = 0, c = 0, d = 0;
  if (!__get_cpuid(1, &a, &b, &c, &d)) return f;
  f.sse2 = (d >> 26) & 1;
  const bool osxsave = (c >> 27) & 1, avx = (c >> 28) & 1, fma = (c >> 12) & 1;
  if (!osxsave || !avx) return f;
  const uint64_t xcr0 = xgetbv0();
  const bool os_ymm = (xcr0 & 0x6) == 0x6;     // SSE and AVX state
  const bool os_zmm = (xcr0 & 0xE6) == 0xE6;   // + opmask, ZMM_Hi256, Hi16_ZMM
  if (!__get_cpuid_count(7, 0, &a, &b, &c, &d)) return f;
  const bool avx2 = (b >> 5) & 1;
  const bool avx512f = (b >> 16) & 1, avx512bw = (b >> 30) & 1, avx512vl = (b >> 31) & 1;
  f.avx2 = os_ymm && avx2 && fma;
  f.avx512 = f.avx2 && os_zmm && avx512f && avx512bw && avx512vl;
  return f;
}
#elif defined(__aarch64__)
// Advanced SIMD is part of every AArch64 CPU; HWCAP is asked anyway.
cpu_features detect() {
  cpu_features f;
  f.neon = (getauxval(AT_HWCAP) & HWCAP_ASIMD) != 0;
  return f;
}
#else
cpu_features detect() { return {}; }
#endif

// The targets: their names, architectures and flags in cpu_features.
struct target_entry {
  const char* name;
  const char* arch;
  bool cpu_features::*runs;
};
#define RAYCAST_ENTRY(name, arch, lanes, needs, flags) {#name, #arch, &cpu_features::name},
constexpr target_entry targets[] = {RAYCAST_TARGETS(RAYCAST_ENTRY)};
#undef RAYCAST_ENTRY

// RAYCAST_MAX_ISA=<target>: every target listed after it, of its architecture (scalar: any), is off.
cpu_features capped(cpu_features f) {
  const char* cap = std::getenv("RAYCAST_MAX_ISA");
  if (!cap) return f;
  const std::string c = cap;
  bool after = false;
  std::string arch;
  for (const target_entry& t : targets) {
    if (after && (arch == "any" || arch == t.arch)) f.*t.runs = false;
    if (c == t.name) after = true, arch = t.arch;
  }
  return f;
}

}  // namespace

std::vector<std::string_view> target_names() {
  std::vector<std::string_view> names;
  for (const target_entry& t : targets) names.emplace_back(t.name);
  return names;
}

std::optional<std::string> unknown_max_isa() {
  const char* cap = std::getenv("RAYCAST_MAX_ISA");
  if (!cap || !*cap) return std::nullopt;
  for (const target_entry& t : targets)
    if (std::string_view(cap) == t.name) return std::nullopt;
  return std::string(cap);
}

const cpu_features& cpu() {
  static const cpu_features f = capped(detect());
  return f;
}

}  // namespace raycast
