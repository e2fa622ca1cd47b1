// The Nano's clock against the Mega's: see nano_clock.h.
#include "nano_clock.h"

#include "fast_div.h"

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
  // us × rate / 2³², rounded; the product's top half, two's complement: adding it subtracts when negative.
  return us + highHalf(static_cast<uint64_t>(static_cast<int64_t>(us) * rate + (int64_t{1} << 31)));
}

}  // namespace mega
