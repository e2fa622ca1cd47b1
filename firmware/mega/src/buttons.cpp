// The panel's buttons, debounced.
#include "buttons.h"

namespace mega {

uint8_t Buttons::sample(uint8_t pressed, uint32_t nowMs) {
  if (started_ && nowMs - lastMs_ < kSampleMs) return 0;
  started_ = true;
  lastMs_ = nowMs;
  uint8_t events = 0;
  for (uint8_t b = 0; b < 3; b++) {
    uint8_t bit = static_cast<uint8_t>(1 << b);
    bool now = pressed & bit, was = state_ & bit;
    if (now == was) {
      count_[b] = 0;
      continue;
    }
    if (++count_[b] < kStable) continue;
    count_[b] = 0;
    state_ ^= bit;
    if (now) events |= bit;
  }
  return events;
}

}  // namespace mega
