// Timer1 drives the step pins from StepEngine::tick() (16 MHz / 8 = the engine's 2 MHz ticks).
#pragma once
#include <stdint.h>

#include <avr/io.h>

#include "pins.h"
#include "step_engine.h"

namespace mega {

// The one step engine: a global at a fixed address, so the interrupt reads its members directly
// instead of through a pointer.
extern StepEngine stepEngine;

// Sets up the pins and the timer.
void stepperBegin();
// Bit a flips axis a's direction pin (invert.x/y/z).
void stepperInvert(uint8_t invert);
// Starts the timer if it stopped and work is queued; call after queueing.
void stepperKick();
// Reads the endstops as the interrupt does (bit a: axis a's switch closed). Inline: the step
// interrupt calls nothing, so it saves only the registers it uses.
__attribute__((always_inline)) inline uint8_t readEndstops() {
  uint8_t bits = 0;
  if (!(ENDSTOP_X_PIN & ENDSTOP_X_BIT)) bits |= 1;
  if (!(ENDSTOP_YZ_PIN & ENDSTOP_Y_BIT)) bits |= 2;
  if (!(ENDSTOP_YZ_PIN & ENDSTOP_Z_BIT)) bits |= 4;
  return bits;
}
// The longest the step interrupt has taken, in timer ticks (0.5 µs).
uint16_t stepperWorstTicks();
// The interrupt's body (called from TIMER1_COMPA_vect).
void stepInterrupt();

}  // namespace mega
