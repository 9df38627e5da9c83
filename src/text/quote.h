// Values in messages: a token quoted and cut short, a number as a person
// writes it. Every room's refusals spell values this way.
#pragma once
#include <string>
#include <string_view>

namespace raycast {

// The token in quotes, at most 32 bytes of it (cut at a character boundary,
// "…" when cut): messages never carry a huge token whole.
std::string quote_token(std::string_view token);

// A number as a person writes it, shortest round trip: 16777216, 0.5, 1e+30.
std::string number_text(double x);

}  // namespace raycast
