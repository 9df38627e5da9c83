// raycast-bench's sphere scenes: rows render/BACKEND/PRECISION/SCENE/WxH/tN/OUT
// for every built-in scene with spheres, every core backend this CPU runs, and
// the book's own ch. 6 program (`book`, bench/book_ch6.h; world only, rgb8,
// one thread), each with its error against the double reference.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

namespace raycast::bench {

void register_sphere_rows(const std::vector<std::pair<int64_t, int64_t>>& sizes,
                          const std::vector<int>& threads);

}  // namespace raycast::bench
