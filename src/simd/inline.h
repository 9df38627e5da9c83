// Every vector operation is forced inline: a helper GCC leaves out of line
// passes its registers through memory (SSE2's two-half types especially) and
// costs more than the instruction it wraps.
#pragma once

#define RAYCAST_INLINE inline __attribute__((always_inline))
