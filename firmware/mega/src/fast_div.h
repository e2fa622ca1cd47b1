// Quotients the Mega needs often, without the AVR's division routines (a 32-bit division takes 36 µs
// there, a 64-bit one 38 µs; profiled in simavr: docs/firmware-mega.md "Measured").
#pragma once
#include <stdint.h>
#include <string.h>

namespace mega {

// The top 32 bits of a 64-bit value, taken as bytes: avr-gcc shifts a 64-bit value by calling a
// bit-by-bit loop. Little-endian, on the AVR and the hosts alike.
inline uint32_t highHalf(uint64_t v) {
  uint8_t b[8];
  memcpy(b, &v, sizeof b);
  return static_cast<uint32_t>(b[4]) | static_cast<uint32_t>(b[5]) << 8 | static_cast<uint32_t>(b[6]) << 16 | static_cast<uint32_t>(b[7]) << 24;
}

// us / 1000, exact for every 32-bit us: floor(us × 274877907 / 2³⁸), the multiplier 2³⁸ / 1000
// rounded up. Its excess (0.056) adds under 2³² × 0.056 / 2³⁸ < 0.001 to us / 1000, whose fraction is
// at most 0.999: never enough to reach the next whole number.
inline uint32_t msOf(uint32_t us) { return highHalf(static_cast<uint64_t>(us) * 274877907u) >> 6; }

}  // namespace mega
