// CR Touch servo signal on D3: a 50 Hz pulse train timed by Timer1 compare B.
//
// Why not the Arduino Servo library: it takes all of Timer1 and changes its prescaler, and the
// exposure timing needs Timer1 at the full clock (led_timer). This shares the free-running
// Timer1: edges are scheduled on compare B relative to the previous edge, so the width does not
// drift with interrupt latency. Both edges see similar latency, which mostly cancels.
#include "servo_pulse.h"

#include <avr/interrupt.h>
#include <avr/io.h>

#include "compare_wake.h"
#include "pins.h"

namespace nano {
namespace servo_pulse {
namespace {

constexpr uint32_t kPeriodTicks = 20000UL * 16;  // 20 ms at 16 MHz
constexpr uint16_t kMinLeadTicks = 512;

volatile uint16_t widthTicks_ = 0;
volatile uint16_t wraps_ = 0;
volatile bool high_ = false;
bool running_ = false;

void scheduleLow(uint16_t width) {
  uint32_t delta = kPeriodTicks - width;
  if ((delta & 0xFFFF) < kMinLeadTicks) delta += kMinLeadTicks;  // keep the first match ahead of the counter
  OCR1B += static_cast<uint16_t>(delta);
  wraps_ = static_cast<uint16_t>(delta >> 16);
}

}  // namespace

void set(uint16_t widthUs) {
  uint8_t sreg = SREG;
  cli();
  widthTicks_ = static_cast<uint16_t>(widthUs * 16u);
  if (!running_) {
    SERVO_PORT &= static_cast<uint8_t>(~_BV(SERVO_BIT));
    SERVO_DDR |= _BV(SERVO_BIT);
    high_ = false;
    wraps_ = 0;
    OCR1B = static_cast<uint16_t>(TCNT1 + 1000);
    TIFR1 = _BV(OCF1B);
    TIMSK1 |= _BV(OCIE1B);
    running_ = true;
  }
  SREG = sreg;
}

bool quietFor(uint16_t ticks) {
  uint8_t sreg = SREG;
  cli();
  bool quiet = compareQuietFor(running_, wraps_, TIFR1 & _BV(OCF1B), OCR1B, TCNT1, ticks);
  SREG = sreg;
  return quiet;
}

}  // namespace servo_pulse
}  // namespace nano

ISR(TIMER1_COMPB_vect) {
  using namespace nano::servo_pulse;
  if (wraps_) {
    wraps_--;
    return;
  }
  uint16_t width = widthTicks_;
  if (high_) {
    SERVO_PORT &= static_cast<uint8_t>(~_BV(SERVO_BIT));
    high_ = false;
    scheduleLow(width);
  } else {
    SERVO_PORT |= _BV(SERVO_BIT);
    high_ = true;
    OCR1B += width;
  }
}
