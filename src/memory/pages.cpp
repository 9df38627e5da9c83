#include "memory/pages.h"

#include <sys/mman.h>

#include <chrono>

namespace raycast {
namespace {

using clock = std::chrono::steady_clock;

// Seconds to map `bytes` afresh with the given advice and touch each of its 4 KiB pages.
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

// Faults in one huge page (its contents kept): whether within 1 ms, as where the host backs it.
bool fault_backed(unsigned char* page) {
  volatile unsigned char* const byte = page;
  const clock::time_point t0 = clock::now();
  *byte = *byte;
  return std::chrono::duration<double>(clock::now() - t0).count() < 1e-3;
}

}  // namespace

bool small_pages_dear() {
  // An unbacked huge page costs about 2 ms a MiB, 7.8 us a 4 KiB page: dear above half that.
  static const bool dear = [] {
    constexpr size_t pages = 128;
    const double s = first_touch(pages << 12, MADV_NOHUGEPAGE);
    return !(s >= 0.0) || s / double(pages) > 4e-6;
  }();
  return dear;
}

void advise_huge_pages(void* p, size_t n, bool always, bool prefault) {
  constexpr uintptr_t huge = huge_page_bytes;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(p) + huge - 1) & ~(huge - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(p) + n) & ~(huge - 1);
  if (end <= begin) return;
  auto* const first = reinterpret_cast<unsigned char*>(begin);
  const size_t bytes = end - begin;
  if (always || small_pages_dear()) {
    ::madvise(first, bytes, MADV_HUGEPAGE);
    return;
  }
  if (!prefault) return;  // small pages: memory that may not all be used
  ::madvise(first, bytes, MADV_HUGEPAGE);
  size_t at = 0;
  while (at < bytes && fault_backed(first + at)) at += huge;
  if (at < bytes) ::madvise(first + at, bytes - at, MADV_NOHUGEPAGE);
}

void* map_huge(size_t n, bool always) {
  const size_t bytes = huge_mapping_bytes(n);
  if (bytes < n) return nullptr;
  void* raw = ::mmap(nullptr, bytes + huge_page_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) return nullptr;
  const uintptr_t start = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = (start + huge_page_bytes - 1) & ~uintptr_t(huge_page_bytes - 1);
  if (aligned > start) ::munmap(raw, aligned - start);
  if (const size_t tail = start + huge_page_bytes - aligned) ::munmap(reinterpret_cast<void*>(aligned + bytes), tail);
  advise_huge_pages(reinterpret_cast<void*>(aligned), bytes, always, true);
  return reinterpret_cast<void*>(aligned);
}

}  // namespace raycast
