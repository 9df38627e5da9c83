#include "prepare/culling.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstdlib>
#include <initializer_list>
#include <optional>

#include "prepare/culling_geometry.h"

namespace raycast {

using namespace culling_detail;

batch_culler::batch_culler(const float_scene& f, size_t most, int shift, int batch, double spread)
    : f_(f), shift_(shift), batch_shift_(std::countr_zero(unsigned(batch))), spread_(spread),
      batches_((f.width + batch - 1) / batch) {
  assert(std::has_single_bit(unsigned(batch)));  // a vector's width: batch_shift_ divides by it
  spans_ = static_cast<sphere_span*>(std::malloc(most * sizeof(sphere_span) + 1));
  capacity_ = std::max(4 * most, budget);
  const size_t batches = size_t(batches_);
  list_ = static_cast<uint32_t*>(std::malloc(capacity_ * sizeof(uint32_t)));
  first_ = static_cast<uint32_t*>(std::malloc((batches + 1) * sizeof(uint32_t)));
  fill_ = static_cast<uint32_t*>(std::malloc((batches + 1) * sizeof(uint32_t)));
  count_ = static_cast<uint32_t*>(std::malloc(batches * sizeof(uint32_t)));
  slot_start_ = static_cast<uint32_t*>(std::malloc(batches * sizeof(uint32_t)));
  if (!spans_ || !list_ || !first_ || !fill_ || !count_ || !slot_start_) {
    release();
    return;
  }
  // Slots share the list's memory: a slot is touched only as far as its list reaches.
  slot_ = std::min<size_t>(capacity_ / batches, UINT32_MAX / batches);
  for (size_t b = 0; b < batches; ++b) slot_start_[b] = uint32_t(b * slot_);
}

batch_culler::~batch_culler() { release(); }

void batch_culler::release() {
  for (void* p : std::initializer_list<void*>{spans_, list_, first_, fill_, count_, slot_start_}) std::free(p);
  spans_ = nullptr;
  list_ = first_ = fill_ = count_ = slot_start_ = nullptr;
}

namespace {

// keep(k, lo, hi) for each of a row's entries whose sphere its rays may come near, with the
// columns [lo, hi] (a tall sphere's from the exact test); false, stopping, where keep is false.
template <class Keep>
bool each_entry(const float_scene& f, float sv, double spread, int shift, const row_entry* entries, size_t count,
                const Keep& keep) {
  std::optional<row_test> exact;
  for (size_t x = 0; x < count; ++x) {
    const row_entry& e = entries[x];
    int64_t lo = int64_t(e.lo) << shift, hi = ((int64_t(e.hi) + 1) << shift) - 1;
    if (e.lo == row_entry::tall) {
      if (!exact) exact.emplace(f, sv, spread);
      if (!exact->columns(e.sphere, lo, hi)) continue;
    }
    if (!keep(e.sphere, lo, hi)) return false;
  }
  return true;
}

}  // namespace

size_t batch_culler::row(float sv, const row_entry* entries, size_t count) {
  b0_ = 0;
  if (row_in_slots(sv, entries, count)) return kept_;
  // A slot would overflow (rare): the spans, which build() counts and then places.
  const int64_t last_batch = batches_ - 1;
  kept_ = 0;
  entries_ = 0;
  start_ = first_;
  each_entry(f_, sv, spread_, shift_, entries, count, [&](uint32_t k, int64_t lo, int64_t hi) {
    const int32_t a = int32_t(std::min(lo >> batch_shift_, last_batch)), b = int32_t(std::min(hi >> batch_shift_, last_batch));
    spans_[kept_++] = {k, a, b};
    entries_ += size_t(b - a + 1);
    return true;
  });
  return kept_;
}

bool batch_culler::row_in_slots(float sv, const row_entry* entries, size_t count) {
  slotted_ = false;
  if (slot_ == 0) return false;
  const int64_t last_batch = batches_ - 1;
  std::fill(count_, count_ + batches_, 0u);
  kept_ = 0;
  // lo, hi >= 0: a shift is the division by the batch's width.
  const bool fit = each_entry(f_, sv, spread_, shift_, entries, count, [&](uint32_t k, int64_t lo, int64_t hi) {
    const int64_t a = std::min(lo >> batch_shift_, last_batch), b = std::min(hi >> batch_shift_, last_batch);
    ++kept_;
    if (b - a <= 1) {  // most spheres: one batch or two, branch-free (where b = a the second
                       // write lands one past the list's end, uncounted: room for it too)
      if (count_[a] + 1 >= slot_ || count_[b] + 1 >= slot_) return false;
      list_[slot_start_[a] + count_[a]++] = k;
      list_[slot_start_[b] + count_[b]] = k;
      count_[b] += uint32_t(b != a);
      return true;
    }
    for (int64_t i = a; i <= b; ++i) {
      if (count_[i] == slot_) return false;
      list_[slot_start_[i] + count_[i]++] = k;
    }
    return true;
  });
  if (!fit) return false;
  slotted_ = true;
  start_ = slot_start_;
  return true;
}

int64_t batch_culler::run_length() const {
  if (slotted_ || entries_ <= capacity_) return batches_;  // the whole row at once
  const int64_t most = int64_t(capacity_ / kept_);
  return std::clamp<int64_t>(most, 1, batches_);
}

void batch_culler::build(int64_t b0, int64_t b1) {
  if (slotted_) return;  // made by row(), for every batch (b0_ = 0)
  b0_ = b0;
  if (kept_ == 0) return;
  const int64_t n = b1 - b0;
  std::fill(fill_, fill_ + n + 1, 0u);
  // A span's batches within the run, as [a, b].
  const auto clip = [b0, b1](const sphere_span& s, int64_t& a, int64_t& b) {
    a = std::max<int64_t>(s.lo, b0);
    b = std::min<int64_t>(s.hi, b1 - 1);
  };
  for (size_t x = 0; x < kept_; ++x) {
    int64_t a = 0, b = 0;
    clip(spans_[x], a, b);
    for (int64_t i = a; i <= b; ++i) ++fill_[i - b0 + 1];
  }
  first_[0] = 0;
  for (int64_t i = 0; i < n; ++i) {
    first_[i + 1] = first_[i] + fill_[i + 1];
    count_[i] = fill_[i + 1];
    fill_[i] = first_[i];
  }
  for (size_t x = 0; x < kept_; ++x) {
    int64_t a = 0, b = 0;
    clip(spans_[x], a, b);
    for (int64_t i = a; i <= b; ++i) list_[fill_[i - b0]++] = spans_[x].sphere;
  }
}

}  // namespace raycast
