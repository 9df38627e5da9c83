// The arrays the renderer hands out, each with the page policy (pages.h) its use calls for.
#pragma once
#include <cstddef>
#include <new>
#include <utility>
#include <vector>

#include "memory/pages.h"

namespace raycast {

// Always: huge pages whatever the faults cost. FilledLater: mapped only where small pages are dear
// (advised huge, faulted in by its fillers), else the C++ allocator's. Blocks under a MiB always
// come from the C++ allocator.
template <class T, bool Always = false, bool FilledLater = false>
struct page_allocator {
  using value_type = T;
  static constexpr size_t mapped_from = size_t(1) << 20;
  template <class U>
  struct rebind {
    using other = page_allocator<U, Always, FilledLater>;
  };

  page_allocator() = default;
  template <class U>
  page_allocator(const page_allocator<U, Always, FilledLater>&) noexcept {}

  T* allocate(size_t n) {
    if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
    const size_t bytes = n * sizeof(T);
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
  // Default construction leaves elements uninitialized: they are filled later.
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) ::new (static_cast<void*>(p)) U;
    else ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const page_allocator<U, Always, FilledLater>&) const noexcept { return true; }

 private:
  // small_pages_dear() is measured once, so a block is freed as it came.
  static bool mapped(size_t bytes) { return bytes >= mapped_from && (!FilledLater || small_pages_dear()); }
};

// Memory filled whole by its writer (map_huge's `prefault` from a MiB on).
template <class T>
using filled_array = std::vector<T, page_allocator<T>>;

// An array read or written out of order: huge pages always, as its TLB misses cost more than its
// faults. Elements are not zeroed unless a value is given.
template <class T>
using out_of_order_array = std::vector<T, page_allocator<T, true>>;

// An array every element of which its filling threads write before it is read (they share its
// first touch). Elements are not zeroed unless a value is given.
template <class T>
using filled_later_array = std::vector<T, page_allocator<T, false, true>>;

}  // namespace raycast
