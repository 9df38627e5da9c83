// Memory for arrays of megabytes -- a scene's spheres, the culling lists --
// with transparent huge pages asked for: filling 100 MB then costs tens of
// page faults rather than tens of thousands, which on some virtual machines
// take longer than the work that fills them (N = 10^6 spheres: preparation
// 0.41 -> 0.13 s here). Advice only: where the kernel does not take it,
// nothing changes but the faults.
#pragma once
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>

namespace raycast {

inline constexpr size_t huge_page_bytes = size_t(2) << 20;

// Asks for huge pages over the 2 MiB pages inside [p, p + n).
inline void advise_huge_pages(void* p, size_t n) {
  constexpr uintptr_t huge = huge_page_bytes;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(p) + huge - 1) & ~(huge - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(p) + n) & ~(huge - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

// n bytes rounded up to whole huge pages.
inline size_t huge_mapping_bytes(size_t n) { return (n + huge_page_bytes - 1) & ~(huge_page_bytes - 1); }

// Fresh zeroed memory for n bytes (n > 0), mapped at a 2 MiB boundary in whole
// huge pages and advised, or nullptr. Both ends aligned matter: a mapping
// that starts or ends inside a huge page is faulted in 4 KiB pages there,
// and 4 MiB arrays (a million floats) would take half their pages that way.
// Free with unmap_huge(p, n).
inline void* map_huge(size_t n) {
  const size_t bytes = huge_mapping_bytes(n);
  if (bytes < n) return nullptr;
  void* raw = ::mmap(nullptr, bytes + huge_page_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) return nullptr;
  const uintptr_t start = reinterpret_cast<uintptr_t>(raw);
  const uintptr_t aligned = (start + huge_page_bytes - 1) & ~uintptr_t(huge_page_bytes - 1);
  if (aligned > start) ::munmap(raw, aligned - start);
  if (const size_t tail = start + huge_page_bytes - aligned) ::munmap(reinterpret_cast<void*>(aligned + bytes), tail);
  ::madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE);
  return reinterpret_cast<void*>(aligned);
}
inline void unmap_huge(void* p, size_t n) { ::munmap(p, huge_mapping_bytes(n)); }

template <class T>
struct huge_page_allocator {
  using value_type = T;
  static constexpr size_t mapped_from = size_t(1) << 20;

  huge_page_allocator() = default;
  template <class U>
  huge_page_allocator(const huge_page_allocator<U>&) noexcept {}

  T* allocate(size_t n) {
    const size_t bytes = n * sizeof(T);
    if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
    if (bytes < mapped_from) return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
    void* p = map_huge(bytes);
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t n) noexcept {
    const size_t bytes = n * sizeof(T);
    if (bytes < mapped_from) ::operator delete(p, std::align_val_t(alignof(T)));
    else unmap_huge(p, bytes);
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) ::new (static_cast<void*>(p)) U;
    else ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const huge_page_allocator<U>&) const noexcept { return true; }
};

}  // namespace raycast
