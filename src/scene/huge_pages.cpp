#include "scene/huge_pages.h"

#include <sys/mman.h>

#include <chrono>

namespace raycast {

namespace {

using clock = std::chrono::steady_clock;

// Seconds to map `bytes` afresh with the given advice and touch each of its
// 4 KiB pages; a huge page is faulted in whole at its first byte.
double first_touch(size_t bytes, int advice) {
  void* p = ::mmap(nullptr, bytes + huge_page_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) return -1.0;
  auto* aligned = reinterpret_cast<volatile char*>((reinterpret_cast<uintptr_t>(p) + huge_page_bytes - 1) &
                                                  ~uintptr_t(huge_page_bytes - 1));
  ::madvise(const_cast<char*>(aligned), bytes, advice);
  const clock::time_point t0 = clock::now();
  for (size_t at = 0; at < bytes; at += 4096) aligned[at] = 1;
  const double s = std::chrono::duration<double>(clock::now() - t0).count();
  ::munmap(p, bytes + huge_page_bytes);
  return s;
}

}  // namespace

bool huge_pages_pay() {
  // A huge page costs about 2 ms a MiB to fault in where the host has not
  // backed it (most of a run's, on a host that hands memory back) and 0.07
  // ms where it has; small pages cost what they cost everywhere. So small
  // pages pay where their faults cost under half the cold huge page's
  // (7.8 us a 4 KiB page): 4 us. One sample of 128 pages decides; timing
  // huge pages instead would need many, as the first are often backed.
  static const bool pay = [] {
    constexpr size_t pages = 128;
    const double s = first_touch(pages << 12, MADV_NOHUGEPAGE);
    return !(s >= 0.0) || s / double(pages) > 4e-6;
  }();
  return pay;
}

}  // namespace raycast
