// Memory for arrays of megabytes -- a scene's spheres, the culling lists --
// in transparent huge pages where they fault in faster than small pages, or
// where they are read or written out of order (out_of_order_array).
// On the virtual machines this project is measured on, a first touch of
// memory costs more than the work that fills it, and which page size costs
// less differs between hosts and between runs. A huge page costs about 2 ms
// a MiB where the host has not backed it yet (a new process, seconds after
// the last) and 0.07 ms where it has (memory a process freed and maps
// again); a 4 KiB page costs about 15 us on some hosts (huge pages twice as
// fast even cold: N = 10^6 spheres prepared in 0.13 s, not 0.41 s) and 1.6
// us on others, 0.4 ms a MiB (small pages five times as fast as cold huge
// pages: 10^6 spheres loaded and prepared in 0.26 s, not 0.5 s). So small
// pages' cost is measured once per process, and where they are cheap an
// array of map_huge gets huge pages only while each faults in as backed
// (advise_huge_pages). Advice only: where the kernel does not take it,
// nothing changes but the faults.
#pragma once
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace raycast {

inline constexpr size_t huge_page_bytes = size_t(2) << 20;

// Whether small pages' faults cost more here than a huge page's where the
// host has not backed it: the first touch of 128 freshly mapped small pages,
// timed once per process (0.2-2 ms) and remembered (huge_pages.cpp).
bool small_pages_dear();

// Asks for huge pages over the 2 MiB pages inside [p, p + n) where they
// fault in faster: always where small pages are dear, or with `always`
// (memory read out of order, whose TLB misses cost more than its faults).
// Elsewhere, with `prefault` (memory the caller fills whole), while the host
// still backs the memory, as each huge page's fault shows (0.15 ms where it
// does, 4 ms where not: a process that frees and maps again, as the bench's
// repetitions do, gets its memory back backed; a new process seconds after
// the last mostly does not): they are faulted in here one by one until one
// is not backed, and the rest is left to small pages; without `prefault`,
// small pages. Contents are kept.
void advise_huge_pages(void* p, size_t n, bool always = false, bool prefault = false);

// n bytes rounded up to whole huge pages.
inline size_t huge_mapping_bytes(size_t n) { return (n + huge_page_bytes - 1) & ~(huge_page_bytes - 1); }

// Fresh zeroed memory for n bytes (n > 0), mapped at a 2 MiB boundary in
// whole huge pages and advised (advise_huge_pages, with `prefault`), or
// nullptr. Both ends aligned matter: a mapping
// that starts or ends inside a huge page is faulted in 4 KiB pages there,
// and 4 MiB arrays (a million floats) would take half their pages that way.
// Free with unmap_huge(p, n).
inline void* map_huge(size_t n, bool always = false) {
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
inline void unmap_huge(void* p, size_t n) { ::munmap(p, huge_mapping_bytes(n)); }

// Always: huge pages whatever the faults cost (map_huge's `always`).
// FilledLater: memory whose every element is written before it is read,
// by as many threads as fill it: mapped only where small pages are dear,
// and then advised huge but not faulted in here (advise_huge_pages: its
// faults are the fillers'); elsewhere the C++ allocator's small pages,
// touched first by the fillers.
template <class T, bool Always = false, bool FilledLater = false>
struct huge_page_allocator {
  using value_type = T;
  static constexpr size_t mapped_from = size_t(1) << 20;
  template <class U>
  struct rebind {
    using other = huge_page_allocator<U, Always, FilledLater>;
  };

  huge_page_allocator() = default;
  template <class U>
  huge_page_allocator(const huge_page_allocator<U, Always, FilledLater>&) noexcept {}

  T* allocate(size_t n) {
    const size_t bytes = n * sizeof(T);
    if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
    if (!mapped(bytes)) return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
    void* p = map_huge(bytes, Always);
    if (!p) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t n) noexcept {
    const size_t bytes = n * sizeof(T);
    if (!mapped(bytes)) ::operator delete(p, std::align_val_t(alignof(T)));
    else unmap_huge(p, bytes);
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) ::new (static_cast<void*>(p)) U;
    else ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const huge_page_allocator<U, Always, FilledLater>&) const noexcept { return true; }

 private:
  // Whether n bytes are mapped (map_huge) rather than the C++ allocator's;
  // small_pages_dear() is measured once, so a block is freed as it came.
  static bool mapped(size_t bytes) { return bytes >= mapped_from && (!FilledLater || small_pages_dear()); }
};

// An array read or written out of order (the light's grid and bins, the
// depth order's indices and keys, a particle file's decoded table): in huge
// pages always, as its TLB misses cost more than its faults (10^8
// spheres with shadows: 59 s, not 76 s). Elements are not zeroed unless a
// value is given.
template <class T>
using out_of_order_array = std::vector<T, huge_page_allocator<T, true>>;

// An array whose every element is written before it is read, by as many
// threads as fill it, so that they share its first touch (a light structure
// of 10^8 spheres: 5 GB, 11 s on one thread): in huge pages where small
// pages are dear (small_pages_dear: over 4 us a page; 10 us on some hosts,
// where the bins of a packed box of 10^6 took 0.26 s to build in small
// pages and 0.16 s in huge ones), small pages elsewhere. Elements are not
// zeroed unless a value is given.
template <class T>
using filled_later_array = std::vector<T, huge_page_allocator<T, false, true>>;

}  // namespace raycast
