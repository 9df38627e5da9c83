// The stiff and extreme inputs as a reusable list: each a
// camera and a sky the renderers must handle like the double reference does.
// Test data: tests/test_numerics.cpp and raycast-bench's stiff section.
#pragma once
#include <vector>

#include "cases.h"

namespace raycast_test {

using stiff_case = scene_case;

// Degenerate sizes, extreme scales, far origins and an HDR sky; every image
// has at most 400 x 225 pixels (aspect 1:100000 is 3 x 300).
std::vector<stiff_case> stiff_cases();

}  // namespace raycast_test
