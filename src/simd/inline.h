// Every vector operation is forced inline: out of line, a helper passes its registers through
// memory, and no copy built with one target's flags may stand in for another's.
#pragma once

#define RAYCAST_INLINE inline __attribute__((always_inline))
