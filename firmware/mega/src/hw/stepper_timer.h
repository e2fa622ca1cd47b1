// Timer1 drives the step pins from StepEngine::tick() (16 MHz / 8 = the engine's 2 MHz ticks).
#pragma once
#include <stdint.h>

#include "step_engine.h"

namespace mega {

// Sets up the pins and the timer; `invert` bit a flips axis a's direction pin (invert.x/y/z).
void stepperBegin(StepEngine& engine);
void stepperInvert(uint8_t invert);
// Starts the timer if it stopped and work is queued; call after queueing.
void stepperKick();
// Reads the endstops as the interrupt does (bit a: axis a's switch closed).
uint8_t readEndstops();
// The longest the step interrupt has taken, in timer ticks (0.5 µs).
uint16_t stepperWorstTicks();
// The interrupt's body (called from TIMER1_COMPA_vect).
void stepInterrupt();

}  // namespace mega
