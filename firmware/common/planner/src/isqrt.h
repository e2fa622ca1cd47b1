// The integer square root the planner's time model and the Mega's step engine share
// (step_profile.cpp's rateAt and time_model.cpp's copy of it must give the same rate, step for step).
// Inline, so each translation unit compiles it where it is used, as the step engine had it.
#pragma once
#include <stdint.h>

namespace uv {

// floor(sqrt(n)), digit by digit: shifts and adds only, no division (the AVR has no divider).
inline uint32_t isqrt32(uint32_t n) {
  uint32_t root = 0, bit = 1ul << 30;
  while (bit > n) bit >>= 2;
  while (bit) {
    if (n >= root + bit) {
      n -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return root;
}

}  // namespace uv
