// When a Timer1 compare channel will next wake its interrupt: the rule led_timer and servo_pulse share.
#pragma once
#include <stdint.h>

namespace nano {

// True when the channel's next handler run is more than `ticks` away (or it is not armed).
// `wraps` compare matches are still to pass before the one that does work; a match that happened
// while interrupts were off is `pending` and would otherwise read as a whole wrap away.
inline bool compareQuietFor(bool armed, uint16_t wraps, bool pending, uint16_t ocr, uint16_t tcnt, uint16_t ticks) {
  if (!armed || wraps > 1) return true;
  if (pending) return false;  // its handler runs as soon as interrupts are on again
  if (wraps == 1) return true;
  return static_cast<uint16_t>(ocr - tcnt) > ticks;
}

}  // namespace nano
