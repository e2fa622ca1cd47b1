// CR Touch servo signal on D3: a 50 Hz pulse train timed by Timer1 compare B.
#pragma once
#include <stdint.h>

namespace nano {
namespace servo_pulse {

// Starts the train, or changes its width from the next pulse on. Needs led_timer::begin() first.
void set(uint16_t widthUs);
// True when no servo edge is due within `ticks` (or no train is running).
bool quietFor(uint16_t ticks);

}  // namespace servo_pulse
}  // namespace nano
