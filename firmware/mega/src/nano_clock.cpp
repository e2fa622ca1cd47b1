// The Nano's clock against the Mega's: see nano_clock.h.
#include "nano_clock.h"

#include <string.h>

namespace mega {

void NanoClock::sample(uint32_t megaUs, uint32_t nanoUs) {
  if (!anchored_) {
    anchored_ = true;
    megaUs0_ = megaUs;
    nanoUs0_ = nanoUs;
    return;
  }
  const uint32_t dm = megaUs - megaUs0_, dn = nanoUs - nanoUs0_;  // both wrap after 71 minutes
  if (dm < kClockBaselineUs) return;
  const int64_t ppm = (static_cast<int64_t>(dn) - static_cast<int64_t>(dm)) * 1000000 / static_cast<int64_t>(dm);
  if (ppm > kClockMaxPpm || ppm < -kClockMaxPpm) {
    known_ = false;
    megaUs0_ = megaUs;
    nanoUs0_ = nanoUs;
    return;
  }
  ppm_ = static_cast<int32_t>(ppm);
  known_ = true;
  if (dm > kClockRebaseUs) {
    megaUs0_ = megaUs;
    nanoUs0_ = nanoUs;
  }
}

int32_t NanoClock::rate(int32_t ppm) {
  const int64_t scaled = static_cast<int64_t>(ppm) * (int64_t{1} << 32);
  return static_cast<int32_t>(scaled >= 0 ? (scaled + 500000) / 1000000 : -((-scaled + 500000) / 1000000));
}

uint32_t NanoClock::toNano(uint32_t us, int32_t rate) {
  // us × rate / 2³², rounded: the product's top four bytes, taken as bytes (an AVR shifts a 64-bit
  // value by calling a loop).
  const int64_t extra = static_cast<int64_t>(us) * rate + (int64_t{1} << 31);
  uint8_t b[8];
  memcpy(b, &extra, sizeof b);  // little-endian, on the AVR and the hosts alike
  const uint32_t high = static_cast<uint32_t>(b[4]) | static_cast<uint32_t>(b[5]) << 8 | static_cast<uint32_t>(b[6]) << 16 | static_cast<uint32_t>(b[7]) << 24;
  return us + high;  // the top half, two's complement: adding it subtracts when negative
}

}  // namespace mega
