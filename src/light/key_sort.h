// A stable grouping of records by a key in [0, keys) (a counting sort) in
// two passes that each stay within the caches. A direct counting sort over a
// million keys waits twice on memory for every record: on its key's counter
// and on its place. Here the records first go to a few hundred bands of
// consecutive keys, written as that many streams, and then each band (a
// buffer the cache holds) to its keys' places.
//
// Use: count(key) for every record, in any order; start(out); put(key,
// record) for every record, in the order they keep within a key; finish(first):
// key k's records at out[first[k] .. first[k + 1]).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "scene/huge_pages.h"

namespace raycast {

template <class Rec>
class key_sort {
 public:
  // records: about how many there will be (it sizes the bands: 4096 records
  // each, at most 1024 of them); keys < 2^32, records < 2^32.
  key_sort() = default;
  key_sort(size_t keys, size_t records) : keys_(keys) {
    const size_t bands = std::clamp<size_t>(records / 4096, 1, 1024);
    while ((size_t(1) << shift_) * bands < keys) ++shift_;  // keys a band: a power of two
    width_ = size_t(1) << shift_;
    start_.assign((keys + width_ - 1) / width_ + 1, 0);
  }
  void count(size_t key) { ++start_[(key >> shift_) + 1]; }
  template <class Array>
  void start(Array& out) {
    for (size_t b = 0; b + 1 < start_.size(); ++b) start_[b + 1] += start_[b];
    fill_.assign(start_.begin(), start_.end() - 1);
    out.resize(start_.back());
    key_.resize(start_.back());
    out_ = out.data();
  }
  void put(size_t key, const Rec& r) {
    const size_t j = fill_[key >> shift_]++;
    out_[j] = r;
    key_[j] = uint32_t(key);
  }
  // then: each_key(begin, end) on each key's records, while its band is in the cache.
  template <class EachKey>
  void finish(out_of_order_array<uint32_t>& first, const EachKey& each_key) {
    first.resize(keys_ + 1);
    std::vector<uint32_t> at(width_ + 1);
    std::vector<Rec> band;
    for (size_t b = 0; b + 1 < start_.size(); ++b) {
      const size_t lo = start_[b], hi = start_[b + 1], k0 = b * width_, k1 = std::min(keys_, k0 + width_);
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
    first[keys_] = uint32_t(start_.back());
    key_ = {};
  }
  void finish(out_of_order_array<uint32_t>& first) {
    finish(first, [](Rec*, Rec*) {});
  }

 private:
  size_t keys_ = 0, width_ = 1;
  int shift_ = 0;
  std::vector<size_t> start_, fill_;  // each band's first record (bands + 1), and its next
  std::vector<uint32_t> key_;  // each placed record's key
  Rec* out_ = nullptr;
};

}  // namespace raycast
