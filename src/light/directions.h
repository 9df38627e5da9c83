// The AO rays' directions in a frame (t, b) about n (light/frame.h) made once
// for a hit's rays (light/directions.cpp; light/secondary.h has the rule).
#pragma once
#include <cstdint>

namespace raycast {

// ao_direction of m numbers (u1, u2) in the frame (t, b) about n, four to a
// vector: the same float operations lane by lane, so the same bits.
void ao_directions_in_frame(const float n[3], const float t[3], const float b[3], const float* u1, const float* u2,
                            uint32_t m, float (*dir)[3]);

}  // namespace raycast
