// A stable least-significant-digit radix sort of 64-bit keys by some of
// their bits, ten at a time: a pass counts each digit, then moves each key to
// its digit's next place. The keys come in `parts` runs (one a thread, each
// counted and moved by one thread, in order), so the order does not depend
// on how many threads run them: part p's keys of a digit follow part p - 1's.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "memory/arrays.h"

namespace raycast {

// Sorts keys by bits [lo, lo + bits) (stable: keys equal there keep their
// order), on `parts` threads; a pass whose digit every key shares is skipped.
inline void radix_sort(out_of_order_array<uint64_t>& keys, int lo, int bits, int parts) {
  constexpr int digit_bits = 10;
  constexpr size_t digits = size_t(1) << digit_bits;
  const size_t n = keys.size();
  parts = std::max(1, parts);
  const auto begin = [&](int p) { return n * size_t(p) / size_t(parts); };
  out_of_order_array<uint64_t> moved;
  moved.resize(n);
  std::vector<size_t> place(size_t(parts) * digits);
  for (int shift = lo; shift < lo + bits; shift += digit_bits) {
    const uint64_t mask = (uint64_t(1) << std::min(digit_bits, lo + bits - shift)) - 1;
    std::fill(place.begin(), place.end(), 0);
#pragma omp parallel for schedule(static, 1) num_threads(parts)
    for (int p = 0; p < parts; ++p)
      for (size_t k = begin(p); k < begin(p + 1); ++k) ++place[size_t(p) * digits + ((keys[k] >> shift) & mask)];
    size_t at = 0;
    bool one_digit = false;
    for (size_t d = 0; d < digits; ++d) {
      const size_t first = at;
      for (int p = 0; p < parts; ++p) {
        const size_t c = place[size_t(p) * digits + d];
        place[size_t(p) * digits + d] = at;
        at += c;
      }
      one_digit = one_digit || at - first == n;
    }
    if (one_digit || n < 2) continue;
#pragma omp parallel for schedule(static, 1) num_threads(parts)
    for (int p = 0; p < parts; ++p)
      for (size_t k = begin(p); k < begin(p + 1); ++k) moved[place[size_t(p) * digits + ((keys[k] >> shift) & mask)]++] = keys[k];
    keys.swap(moved);
  }
}

}  // namespace raycast
