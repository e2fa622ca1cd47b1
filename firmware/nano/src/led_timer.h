// Exposure timing on Timer1 compare A: the LEDs take each new state in one port write at its tick,
// ±0.5 µs, for an F (on together, each off at its own tick) or a scan program's chain of events.
#pragma once
#include <stdint.h>

#include "fire_plan.h"
#include "scan_store.h"

namespace nano {
namespace led_timer {

void begin();  // Timer1 free-running at 16 MHz (shared with servo_pulse on compare B)
void fire(const FirePlan& plan);
// Runs the store's started chain with its time 0 at Timer1 count `time0` (still ahead).
void run(ScanStore& store, uint16_t time0);
// Every LED off in one write, and nothing more switches; true if one was lit or an event pending.
// Safe from an interrupt handler, even one that interrupted the timer's own wait.
bool allOff();
uint8_t lit();
// Whether allOff() cut a run short since the last call, and when: ticks (16 a µs) after the F's
// on-edge, or after the last event a scan chain made (negative before time 0). The dose records
// take the cut's moment from it (dose_tally.h); the timer itself keeps no tally.
bool takeCut(int32_t& ticks);
// True when no switching work starts within `ticks` (so a 35 µs NeoPixel write cannot delay one).
bool quietFor(uint16_t ticks);

}  // namespace led_timer
}  // namespace nano
