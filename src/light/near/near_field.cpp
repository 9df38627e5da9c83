#include "light/near/near_field.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

namespace raycast {
namespace {

std::atomic<uint64_t> next_id{1};

// A record: this header (16 words: the two lists' counts, whether each is
// whole, where each list's blocks start), then the blocks.
enum header : int { ball_count, shadow_count, whole, ball_at, shadow_at, header_words = 16 };
constexpr uint32_t block_words = 64;  // 16 spheres: x[16] y[16] z[16] r[16]

uint32_t blocks_of(uint32_t n) { return (n + 15) / 16; }

// Rows x, y, z, r of n spheres, entry order[i] (or i) as the i-th, as blocks
// at out, NaN past n.
void write_blocks(float* const rows[4], const uint32_t* order, uint32_t n, float* out) {
  for (uint32_t i = 0; i < blocks_of(n) * 16; ++i) {
    float* block = out + (i / 16) * block_words + i % 16;
    const uint32_t e = order && i < n ? order[i] : i;
    for (int a = 0; a < 4; ++a) block[16 * a] = i < n ? rows[a][e] : std::numeric_limits<float>::quiet_NaN();
  }
}

float float_of(uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

near_lists read(const float* rec) {
  near_lists l;
  uint32_t h[shadow_at + 1];
  std::memcpy(h, rec, sizeof h);
  l.ball = {rec + h[ball_at], h[ball_count]};
  l.shadow = {rec + h[shadow_at], h[shadow_count]};
  l.ball_whole = (h[whole] & 1u) != 0;
  l.shadow_whole = (h[whole] & 2u) != 0;
  return l;
}

}  // namespace

near_settings near_settings_for(const sphere_bvh& bvh, bool shadows, const float light[3], bool ao, float ao_distance) {
  near_settings s;
  s.shadows = shadows;
  for (int a = 0; a < 3; ++a) s.light[a] = light[a];
  if (!ao || bvh.size() == 0) return s;
  constexpr double whole_distance = 256, otherwise = 64;  // spheres a ball list holds on average
  const double ball = 4.0 / 3.0 * 3.14159265358979323846 * bvh.density(), rt = bvh.typical_radius();
  const auto expected = [&](double reach) { return ball * (reach + 2 * rt) * (reach + 2 * rt) * (reach + 2 * rt); };
  if (expected(double(ao_distance)) <= whole_distance) {
    s.reach = ao_distance;
  } else {
    const double reach = std::cbrt(otherwise / ball) - 2 * rt;
    s.reach = float(std::min(double(ao_distance), std::max(reach, rt)));
  }
  if (!(s.reach > 0)) s.reach = float(std::max(rt, 1e-30));
  return s;
}

// A thread's ring of records and the table of where each sphere's is: the
// ring's words written since it began (a record lies at head % ring words
// and is whole while head has not gone a ring past it), and by position
// hash, each kept sphere's position and record. The ring starts at 256 KiB
// and doubles (forgetting what it held) when it comes round to its start
// after a sphere was asked for again whose record it had overwritten, up to
// 2 MiB: a small picture's rows need less.
struct near_field::cache {
  uint64_t owner = 0;
  filled_array<float> ring;
  uint64_t head = 0;
  bool overrun = false;  // a sphere's record was overwritten before it was asked for again
  struct entry {
    uint32_t position = ~0u;
    uint64_t at = 0;
  };
  std::vector<entry> table;
  std::vector<float> big;  // a record longer than the ring allows
};

namespace {
constexpr uint64_t most_ring_words = near_field::ring_bytes / 4, first_ring_words = most_ring_words / 8;
}

near_field::near_field(const sphere_bvh& bvh, const near_settings& s, const light_kernels& k)
    : bvh_(bvh), view_(bvh.view()), settings_(s), k_(k), id_(next_id.fetch_add(1)) {}

// Gathers sphere p's lists and writes its record at the ring's head (at:
// where, in words written since the ring began) or, where it would not fit,
// into c.big; returns it.
float* near_field::gather(uint32_t p, cache& c, uint64_t& at) const {
  constexpr uint32_t room = most_listed + 16;
  thread_local std::vector<float> storage(8 * room + room);
  thread_local std::vector<uint32_t> order(room);
  float* const ball[4] = {&storage[0], &storage[room], &storage[2 * room], &storage[3 * room]};
  float* const shadow[4] = {&storage[4 * room], &storage[5 * room], &storage[6 * room], &storage[7 * room]};
  float* const along = &storage[8 * room];
  const sphere4 sp = bvh_.at(p);
  const float* s = sp.v;
  uint32_t nb = 0, ns = 0;
  bool ball_whole = settings_.reach > 0, shadow_whole = settings_.shadows;
  if (ball_whole) {
    // Every sphere that can meet a ray of this one within reach, and a 2^-12 more.
    const float within = (s[3] + settings_.reach) * (1.0f + 0x1p-12f) + 0x1p-20f;
    nb = k_.gather_ball(view_, s, within, p, ball, most_listed);
    ball_whole = nb <= most_listed;
    nb = ball_whole ? nb : 0;
  }
  if (shadow_whole) {
    const float slack = (s[3] + view_.max_r) * 0x1p-12f + 0x1p-20f;
    ns = k_.gather_capsule(view_, s, s[3], settings_.light, slack, p, shadow, along, most_listed);
    shadow_whole = ns <= most_listed;
    ns = shadow_whole ? ns : 0;
  }
  const uint32_t words = header_words + (blocks_of(nb) + blocks_of(ns)) * block_words;
  float* rec = nullptr;
  if (words * 8 <= first_ring_words) {  // a record of up to an eighth of the smallest ring
    const uint64_t ring = c.ring.size();
    if (c.head % ring + words > ring) {  // at the ring's end: grow it (and forget it), or go to its start
      if (c.overrun && ring < most_ring_words) {
        c.ring.assign(2 * ring, 0.0f);
        for (cache::entry& e : c.table) e = {};
        c.head = 0, c.overrun = false;
        bytes_.fetch_add(ring * 4, std::memory_order_relaxed);
      } else {
        c.head += ring - c.head % ring;
      }
    }
    at = c.head;
    rec = c.ring.data() + at % c.ring.size();
    c.head += words;
  } else {
    c.big.resize(words);
    rec = c.big.data();
  }
  uint32_t h[header_words] = {};
  h[ball_count] = nb, h[shadow_count] = ns;
  h[whole] = uint32_t(ball_whole) | uint32_t(shadow_whole) << 1;
  h[ball_at] = header_words, h[shadow_at] = header_words + blocks_of(nb) * block_words;
  for (int w = 0; w < header_words; ++w) rec[w] = float_of(h[w]);
  write_blocks(ball, nullptr, nb, rec + h[ball_at]);
  // In order along the light (ties as gathered): the first blocker ends a ray's scan.
  for (uint32_t i = 0; i < ns; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.begin() + ns, [&](uint32_t x, uint32_t y) { return along[x] < along[y]; });
  write_blocks(shadow, order.data(), ns, rec + h[shadow_at]);
  lists_.fetch_add(1, std::memory_order_relaxed);
  return rec;
}

near_lists near_field::of(uint32_t p) const {
  thread_local cache c;
  if (c.owner != id_) {
    c.ring.assign(first_ring_words, 0.0f);
    c.table.assign(table_entries, {});
    c.owner = id_, c.head = 0;
    bytes_.fetch_add(first_ring_words * 4 + table_entries * sizeof(cache::entry), std::memory_order_relaxed);
  }
  cache::entry& e = c.table[(p * 2654435761u) >> 20];
  // Whole while no later record has come a ring round onto it.
  if (e.position == p && c.head <= e.at + c.ring.size()) return read(c.ring.data() + e.at % c.ring.size());
  c.overrun = c.overrun || e.position == p;
  uint64_t at = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const float* rec = gather(p, c, at);
  const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count();
  nanoseconds_.fetch_add(uint64_t(ns), std::memory_order_relaxed);
  if (rec != c.big.data()) e = {p, at};
  return read(rec);
}

}  // namespace raycast
