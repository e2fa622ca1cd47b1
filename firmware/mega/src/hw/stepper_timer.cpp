// Timer1 drives the step pins from StepEngine::tick(). The interrupt first ends the previous step
// pulse (it was high for a whole interval, far over the drivers' 2 µs), reads the endstops, asks
// the engine, sets the direction pins (and waits their 1 µs setup time only when they changed),
// raises the step pins and sets the next interval.
#include "hw/stepper_timer.h"

#include <Arduino.h>
#include <util/delay.h>

#include "hw/nano_uart.h"
#include "pins.h"

namespace mega {

StepEngine stepEngine;

namespace {
volatile bool running = false;
volatile uint8_t invertBits = 0;
volatile uint16_t worst = 0;
uint8_t pinsDir = 0;  // what the direction pins show now
// How long after its compare match a step usually comes (ticks), and how much later than that a
// scan pass's G went out with its step, still to be added to the intervals that follow.
uint16_t usualStepped = 0;
uint16_t markLate = 0;
}  // namespace

void stepperBegin() {
  const uint8_t outputs[] = {PIN_X_STEP, PIN_Y_STEP, PIN_Z_STEP, PIN_X_DIR, PIN_Y_DIR, PIN_Z_DIR};
  for (uint8_t p : outputs) {
    digitalWrite(p, LOW);
    pinMode(p, OUTPUT);
  }
  pinMode(PIN_X_MIN, INPUT_PULLUP);
  pinMode(PIN_Y_MIN, INPUT_PULLUP);
  pinMode(PIN_Z_MIN, INPUT_PULLUP);
  TCCR1A = 0;
  TCCR1B = (1 << WGM12) | (1 << CS11);  // CTC on OCR1A, clock / 8
  OCR1A = 0xffff;
}

void stepperInvert(uint8_t invert) { invertBits = invert; }

void stepperKick() {
  if (running || stepEngine.idle()) return;
  uint8_t sreg = SREG;
  cli();
  running = true;
  TCNT1 = 0;
  OCR1A = 100;  // the first step in 50 µs
  TIFR1 = (1 << OCF1A);
  TIMSK1 |= (1 << OCIE1A);
  SREG = sreg;
}

uint16_t stepperWorstTicks() {
  uint8_t sreg = SREG;
  cli();
  uint16_t w = worst;
  SREG = sreg;
  return w;
}

namespace {
// The rest of the interrupt, for the tick the engine gave: inlined into both of its paths.
inline void stepWith(StepTick t) __attribute__((always_inline));
// While a glide runs (StepEngine::twoTimings): out of line, so the usual path keeps its tick in registers.
__attribute__((noinline)) void glidingInterrupt() { stepWith(stepEngine.tickGliding(readEndstops())); }
}  // namespace

void stepInterrupt() {
  STEP_XY_PORT &= static_cast<uint8_t>(~(STEP_X_BIT | STEP_Y_BIT));
  STEP_Z_PORT &= static_cast<uint8_t>(~STEP_Z_BIT);
  if (stepEngine.twoTimings()) return glidingInterrupt();
  stepWith(stepEngine.tickBlocks(readEndstops()));
}

namespace {
inline void stepWith(StepTick t) {
  if (t.idle) {
    TIMSK1 &= static_cast<uint8_t>(~(1 << OCIE1A));
    running = false;
    return;
  }
  uint8_t dir = t.dirNeg ^ invertBits;
  if (dir != pinsDir) {
    pinsDir = dir;
    if (dir & 1) DIR_X_PORT |= DIR_X_BIT; else DIR_X_PORT &= static_cast<uint8_t>(~DIR_X_BIT);
    if (dir & 2) DIR_YZ_PORT |= DIR_Y_BIT; else DIR_YZ_PORT &= static_cast<uint8_t>(~DIR_Y_BIT);
    if (dir & 4) DIR_YZ_PORT |= DIR_Z_BIT; else DIR_YZ_PORT &= static_cast<uint8_t>(~DIR_Z_BIT);
    _delay_us(1);  // the drivers' direction setup time before a step edge
  }
  if (t.step & 1) STEP_XY_PORT |= STEP_X_BIT;
  if (t.step & 2) STEP_XY_PORT |= STEP_Y_BIT;
  if (t.step & 4) STEP_Z_PORT |= STEP_Z_BIT;
  const uint16_t stepped = TCNT1;  // how long after its compare match this step came
  if (t.mark) {  // with its step: the head's place is known
    bool sent = nanoUartSendMark();
    stepEngine.markSent(sent);
    if (sent && stepped > usualStepped) markLate = static_cast<uint16_t>(stepped - usualStepped);
  }
  // A minimum that leaks upwards a tick a step: what the steps around take when nothing holds them
  // up, which one held-up step does not move.
  if (stepped <= usualStepped) usualStepped = stepped;
  else usualStepped++;
  uint16_t took = TCNT1;  // ticks since this compare match (the timer restarted from 0 then)
  // In CTC mode the period is OCR1A + 1 ticks (the count runs 0 to OCR1A inclusive). Never set a
  // compare the counter has already passed: it would wait a whole 32 ms wrap.
  uint16_t top = static_cast<uint16_t>(t.interval - 1);
  // The Nano's time 0 follows the G, which goes out with its step, so both are as late as this
  // interrupt ran after its compare match. Steps in a run are late by about the same, the time this
  // interrupt takes to raise the pins, and the head follows the steps. But when other interrupts
  // held up the marked step, or its segment took longer to start, the whole pass's light came that
  // much later against the head (7 to 22 µs a pass in scan_sim_test, moving with unrelated changes
  // to this image). So the head is held back by how much later the marked step came than steps
  // usually do: the next steps each wait up to a quarter interval longer, all before the pass's
  // start mark, at least 1170 µs after the G.
  if (markLate) {
    uint16_t piece = t.interval >> 2;
    if (piece > markLate) piece = markLate;
    if (top <= 0xFFFF - piece) {
      top = static_cast<uint16_t>(top + piece);
      markLate = static_cast<uint16_t>(markLate - piece);
    }
  }
  OCR1A = top > took + 4 ? top : took + 4;
  if (took > worst) worst = took;
}
}  // namespace

}  // namespace mega

ISR(TIMER1_COMPA_vect) { mega::stepInterrupt(); }
