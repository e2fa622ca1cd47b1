// A glide's plan: see glide.h.
#include "glide.h"

#include "isqrt.h"

namespace uv {

bool planGlide(uint32_t steps, uint32_t rate, uint32_t accel, GlidePlan& out) {
  out = GlidePlan{0, 0};
  if (steps == 0 || steps > kGlideMaxSteps || accel == 0 || rate == 0) return false;
  // √(2/a) s in 0.5 µs ticks: √(8·10¹² / a), to the nearest tick. Under 7451 steps/s² it is over 15 bits.
  const uint64_t sq = 8000000000000ull / accel;
  if (sq > static_cast<uint64_t>(kGlideMaxInterval) * kGlideMaxInterval) return false;
  uint32_t c0 = isqrt32(static_cast<uint32_t>(sq));
  if (static_cast<uint64_t>(c0) * c0 + c0 < sq) c0++;  // round to nearest: (c0 + ½)² = c0² + c0 + ¼
  if (c0 > kGlideMaxInterval) return false;
  uint32_t shortest = (2000000u + rate - 1) / rate;  // the rate's interval, rounded up
  if (shortest < 125) shortest = 125;                // 16000 steps/s
  Glide g{static_cast<uint16_t>(c0), static_cast<uint8_t>(steps), static_cast<uint8_t>(steps)};
  out.first = g.interval;
  for (;;) {
    if (g.interval < shortest) return false;
    out.ticks += g.interval;
    if (--g.left == 0) return true;
    g.interval = glideNext(g);
  }
}

}  // namespace uv
