// Values in messages: a token quoted and cut short, a number as a person
// writes it. Every room's refusals spell values this way.
#pragma once
#include <string>
#include <string_view>

namespace raycast {

// Control bytes (below 0x20, and 0x7f) as \xNN, the rest as it is: a
// message is one line of text whatever bytes a file held.
std::string control_escaped(std::string_view text);

// The token in quotes, at most 32 bytes of it (cut at a character boundary,
// "…" when cut), control bytes escaped: messages never carry a huge token
// whole, a newline or a NUL.
std::string quote_token(std::string_view token);

// A number as a person writes it, shortest round trip: 16777216, 0.5, 1e+30.
std::string number_text(double x);

}  // namespace raycast
