// Exposure timing on Timer1 compare A: LEDs on in one port write, each off at its own tick, ±0.5 µs.
#pragma once
#include <stdint.h>

#include "fire_plan.h"

namespace nano {
namespace led_timer {

void begin();  // Timer1 free-running at 16 MHz (shared with servo_pulse on compare B)
void fire(const FirePlan& plan);
void allOff();
uint8_t lit();
// True when no switch-off work starts within `ticks` (so a 35 µs NeoPixel write cannot delay one).
bool quietFor(uint16_t ticks);

}  // namespace led_timer
}  // namespace nano
