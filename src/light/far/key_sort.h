// A stable grouping of records by a key in [0, keys) (a counting sort) in
// two passes that each stay within the caches. A direct counting sort over a
// million keys waits twice on memory for every record: on its key's counter
// and on its place. Here the records first go to a few hundred bands of
// consecutive keys, written as that many streams, and then each band (a
// buffer the cache holds) to its keys' places.
//
// The records come in `parts` (one a thread), each a run of them in order:
// part p's records of a key follow part p - 1's. Use: count(p, key) for
// every record; start(out); put(p, key, record) for every record, part p's
// in the order they keep within a key; finish(first, each_key, threads):
// key k's records at out[first[k] .. first[k + 1]), each_key(begin, end)
// called on each key's records while its band is in the cache. The result
// does not depend on how many threads run the parts, only on the parts.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "memory/arrays.h"

namespace raycast {

// Part p of `parts`' run of n records: [n p / parts, n (p + 1) / parts).
inline size_t part_begin(size_t n, int p, int parts) { return n * size_t(p) / size_t(parts); }

template <class Rec>
class key_sort {
 public:
  // records: about how many there will be (it sizes the bands: 4096 records
  // each, at most 1024 of them); keys < 2^32, records < 2^32.
  key_sort() = default;
  key_sort(size_t keys, size_t records, int parts = 1) : keys_(keys), parts_(size_t(std::max(parts, 1))) {
    const size_t bands = std::clamp<size_t>(records / 4096, 1, 1024);
    while ((size_t(1) << shift_) * bands < keys) ++shift_;  // keys a band: a power of two
    bands_ = (keys + (size_t(1) << shift_) - 1) >> shift_;
    fill_.assign(parts_ * bands_, 0);
  }
  void count(int part, size_t key) { ++fill_[size_t(part) * bands_ + (key >> shift_)]; }
  // Sizes out (whose elements need not be zeroed: each is written) and key_.
  template <class Array>
  void start(Array& out) {
    start_.assign(bands_ + 1, 0);
    size_t at = 0;
    for (size_t b = 0; b < bands_; ++b) {
      start_[b] = at;
      for (size_t p = 0; p < parts_; ++p) {
        const size_t n = fill_[p * bands_ + b];
        fill_[p * bands_ + b] = at;
        at += n;
      }
    }
    start_[bands_] = at;
    out.resize(at);
    key_.resize(at);
    out_ = out.data();
  }
  void put(int part, size_t key, const Rec& r) {
    const size_t j = fill_[size_t(part) * bands_ + (key >> shift_)]++;
    out_[j] = r;
    key_[j] = uint32_t(key);
  }
  template <class EachKey>
  void finish(out_of_order_array<uint32_t>& first, const EachKey& each_key, int threads = 1) {
    first.resize(keys_ + 1);
#pragma omp parallel num_threads(std::max(threads, 1))
    {
      std::vector<uint32_t> at((size_t(1) << shift_) + 1);
      std::vector<Rec> band;
#pragma omp for schedule(dynamic, 4)
      for (size_t b = 0; b < bands_; ++b) finish_band(b, first, each_key, at, band);
    }
    first[keys_] = uint32_t(start_[bands_]);
    key_ = {};
  }
  void finish(out_of_order_array<uint32_t>& first, int threads = 1) {
    finish(first, [](Rec*, Rec*) {}, threads);
  }

 private:
  // Band b's records to their keys' places; at and band: scratch.
  template <class EachKey>
  void finish_band(size_t b, out_of_order_array<uint32_t>& first, const EachKey& each_key, std::vector<uint32_t>& at,
                   std::vector<Rec>& band) {
    const size_t lo = start_[b], hi = start_[b + 1], k0 = b << shift_, k1 = std::min(keys_, k0 + at.size() - 1);
    std::fill(at.begin(), at.end(), 0);
    at[0] = uint32_t(lo);
    for (size_t j = lo; j < hi; ++j) ++at[key_[j] - k0 + 1];
    for (size_t k = k0; k < k1; ++k) {  // at[k - k0]: key k's first place
      first[k] = at[k - k0];
      at[k - k0 + 1] += at[k - k0];
    }
    band.assign(out_ + lo, out_ + hi);
    for (size_t j = lo; j < hi; ++j) out_[at[key_[j] - k0]++] = band[j - lo];
    for (size_t k = k0; k < k1; ++k) each_key(out_ + first[k], out_ + at[k - k0]);
  }

  size_t keys_ = 0, parts_ = 1, bands_ = 0;
  int shift_ = 0;
  std::vector<size_t> start_;  // each band's first record (bands + 1)
  std::vector<size_t> fill_;   // per part and band: its count, then its next place
  filled_later_array<uint32_t> key_;  // each placed record's key
  Rec* out_ = nullptr;
};

}  // namespace raycast
