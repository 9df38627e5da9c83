// The page-size policy, decided here only: whether memory of megabytes is backed by 4 KiB pages or
// 2 MiB transparent huge pages. Which costs less to touch first differs between hosts, so small
// pages' cost is measured once per process (small_pages_dear). Advice only: the faults change,
// nothing else.
#pragma once
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>

namespace raycast {

inline constexpr size_t huge_page_bytes = size_t(2) << 20;

// Whether small pages' faults cost more here than half an unbacked huge page's (128 timed once).
bool small_pages_dear();

// Asks for huge pages over the whole 2 MiB pages inside [p, p + n) where small pages are dear or
// with `always`; else with `prefault` (memory the caller fills whole) huge pages while the host
// backs them (faulted in here until one is not), small pages for the rest. Contents are kept.
void advise_huge_pages(void* p, size_t n, bool always = false, bool prefault = false);

// n bytes rounded up to whole huge pages.
inline size_t huge_mapping_bytes(size_t n) { return (n + huge_page_bytes - 1) & ~(huge_page_bytes - 1); }

// Fresh zeroed memory for n > 0 bytes in whole aligned huge pages (prefaulted), or nullptr.
void* map_huge(size_t n, bool always = false);
inline void unmap_huge(void* p, size_t n) { ::munmap(p, huge_mapping_bytes(n)); }

}  // namespace raycast
