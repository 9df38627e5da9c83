// A stable grouping of records by key, keys in [0, keys), where a record may
// have several keys (a sphere's disc overlaps a few cells): in two passes
// that each stay within the caches. A direct counting sort over a million
// keys waits twice on memory for every record's key: on its counter and on
// its place. Here the records first go to a few hundred bands of consecutive
// keys, written as that many streams, a record once to each band it has keys
// in; then each band (a buffer the cache holds) goes to its keys' places, a
// record copied to each of its keys there. The streams are written where
// their bands' groups will lie, so the build's memory is the output and one
// band's scratch a thread.
//
// keys_of(rec, f) calls f(key) for each of rec's keys, in ascending order,
// the same keys each time it is asked. The records come in `parts` (one a
// thread), each a run of them in order: part p's records of a key follow
// part p - 1's. Use: count(p, rec) for every record; start(out); put(p, rec)
// for every record, part p's in the same order; finish(first, each_key,
// threads): key k's records at out[first[k] .. first[k + 1]), each_key(begin,
// end) called on each key's records while its band is in the cache. The
// result does not depend on how many threads run the parts, only on the
// parts.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "memory/arrays.h"

namespace raycast {

// Part p of `parts`' run of n records: [n p / parts, n (p + 1) / parts).
inline size_t part_begin(size_t n, int p, int parts) { return n * size_t(p) / size_t(parts); }

template <class Rec, class KeysOf>
class key_sort {
 public:
  // placed: about how many (record, key) pairs there will be (it sizes the
  // bands: 4096 pairs each, at most 1024 of them); keys < 2^32, pairs < 2^32.
  key_sort(size_t keys, size_t placed, int parts, KeysOf keys_of)
      : keys_(keys), parts_(size_t(std::max(parts, 1))), keys_of_(keys_of) {
    const size_t bands = std::clamp<size_t>(placed / 4096, 1, 1024);
    while ((size_t(1) << shift_) * bands < keys) ++shift_;  // keys a band: a power of two
    bands_ = (keys + (size_t(1) << shift_) - 1) >> shift_;
    placed_.assign(parts_ * bands_, 0);
    streamed_.assign(parts_ * bands_, 0);
  }
  // Counts rec's keys and bands; returns how many keys it has.
  size_t count(int part, const Rec& r) {
    size_t* placed = &placed_[size_t(part) * bands_];
    size_t* streamed = &streamed_[size_t(part) * bands_];
    size_t last = ~size_t(0), m = 0;
    keys_of_(r, [&](size_t key) {
      const size_t b = key >> shift_;
      ++placed[b], ++m;
      if (b != last) ++streamed[b], last = b;
    });
    return m;
  }
  // Sizes out (whose elements need not be zeroed: each is written).
  template <class Array>
  void start(Array& out) {
    start_.assign(bands_ + 1, 0);
    records_.assign(bands_, 0);
    size_t at = 0;
    for (size_t b = 0; b < bands_; ++b) {
      start_[b] = at;
      size_t stream = at;  // a band's stream: its parts' records in order, from its start
      for (size_t p = 0; p < parts_; ++p) {
        at += placed_[p * bands_ + b];
        records_[b] += streamed_[p * bands_ + b];
        const size_t n = streamed_[p * bands_ + b];
        streamed_[p * bands_ + b] = stream;  // now: part p's next place in band b's stream
        stream += n;
      }
    }
    start_[bands_] = at;
    placed_ = {};
    out.resize(at);
    out_ = out.data();
  }
  void put(int part, const Rec& r) {
    size_t* next = &streamed_[size_t(part) * bands_];
    size_t last = ~size_t(0);
    keys_of_(r, [&](size_t key) {
      const size_t b = key >> shift_;
      if (b != last) out_[next[b]++] = r, last = b;
    });
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
  }
  void finish(out_of_order_array<uint32_t>& first, int threads = 1) {
    finish(first, [](Rec*, Rec*) {}, threads);
  }

 private:
  // Band b's records to their keys' places; at and band: scratch.
  template <class EachKey>
  void finish_band(size_t b, out_of_order_array<uint32_t>& first, const EachKey& each_key, std::vector<uint32_t>& at,
                   std::vector<Rec>& band) {
    const size_t lo = start_[b], k0 = b << shift_, k1 = std::min(keys_, k0 + at.size() - 1);
    const auto in_band = [&](const Rec& r, auto&& f) {
      keys_of_(r, [&](size_t key) {
        if (key >= k0 && key < k1) f(key - k0);
      });
    };
    band.assign(out_ + lo, out_ + lo + records_[b]);
    std::fill(at.begin(), at.end(), 0);
    at[0] = uint32_t(lo);
    for (const Rec& r : band) in_band(r, [&](size_t k) { ++at[k + 1]; });
    for (size_t k = k0; k < k1; ++k) {  // at[k - k0]: key k's first place
      first[k] = at[k - k0];
      at[k - k0 + 1] += at[k - k0];
    }
    for (const Rec& r : band) in_band(r, [&](size_t k) { out_[at[k]++] = r; });
    for (size_t k = k0; k < k1; ++k) each_key(out_ + first[k], out_ + at[k - k0]);
  }

  size_t keys_ = 0, parts_ = 1, bands_ = 0;
  int shift_ = 0;
  KeysOf keys_of_;
  std::vector<size_t> start_;    // each band's first place (bands + 1)
  std::vector<size_t> records_;  // each band's records in its stream
  std::vector<size_t> placed_;   // per part and band: its (record, key) pairs
  std::vector<size_t> streamed_;  // per part and band: its records, then its next place in the stream
  Rec* out_ = nullptr;
};

}  // namespace raycast
