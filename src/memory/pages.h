// The page-size policy: whether memory of megabytes is backed by 4 KiB pages
// or 2 MiB transparent huge pages, decided here and nowhere else.
//
// A first touch of fresh memory can cost more than the work that fills it,
// and which page size costs less differs between hosts: a huge page costs
// little where the host already backs it and much where it does not; small
// pages cost the same everywhere, but that cost varies by host over a range
// of ten. So small pages' cost is measured once per process
// (small_pages_dear), and memory is advised accordingly. Advice only: where
// the kernel does not take it, nothing changes but the faults.
#pragma once
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>

namespace raycast {

inline constexpr size_t huge_page_bytes = size_t(2) << 20;

// Whether small pages' faults cost more here than half a huge page's where
// the host has not backed it: the first touch of 128 freshly mapped small
// pages, timed once per process and remembered.
bool small_pages_dear();

// Asks for huge pages over the whole 2 MiB pages inside [p, p + n): always
// where small pages are dear, or with `always` (memory read out of order,
// whose TLB misses cost more than its faults). Elsewhere, with `prefault`
// (memory the caller fills whole), huge pages while the host still backs
// them (each faulted in here until one is not), small pages for the rest;
// without `prefault`, small pages. Contents are kept.
void advise_huge_pages(void* p, size_t n, bool always = false, bool prefault = false);

// n bytes rounded up to whole huge pages.
inline size_t huge_mapping_bytes(size_t n) { return (n + huge_page_bytes - 1) & ~(huge_page_bytes - 1); }

// Fresh zeroed memory for n bytes (n > 0), mapped at a 2 MiB boundary in
// whole huge pages (a mapping that starts or ends inside one is faulted in
// small pages there) and advised with `prefault`, or nullptr. Free with
// unmap_huge(p, n).
void* map_huge(size_t n, bool always = false);
inline void unmap_huge(void* p, size_t n) { ::munmap(p, huge_mapping_bytes(n)); }

}  // namespace raycast
