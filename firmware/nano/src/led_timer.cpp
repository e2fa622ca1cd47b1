// Exposure timing on Timer1 compare A: LEDs on in one port write, each off at its own tick, ±0.5 µs.
//
// Why it wakes early and spins: the compare interrupt can be held up by another interrupt
// (UART, ADC, Timer0, servo: each under 6 µs). So the compare is set kMarginTicks before the
// switch-off, and the handler waits on TCNT1 with interrupts off for the exact tick. The off-edge
// then lands within one pass of the wait loop (8 cycles) of the target, whatever else is running.
// Timer1 counts at the CPU clock and wraps every 4.096 ms; longer exposures count compare
// matches (`wraps_`) until the last one.
#include "led_timer.h"

#include <avr/interrupt.h>
#include <avr/io.h>

#include "compare_wake.h"
#include "pins.h"

namespace nano {
namespace led_timer {
namespace {

constexpr uint16_t kMarginTicks = 256;   // wake 16 µs before a switch-off
constexpr uint16_t kMinLeadTicks = 256;  // never arm a compare closer than 16 µs ahead
// The wait loop leaves 5-9 cycles after the target tick (one 8-cycle pass of the loop plus the
// port write), measured on the pins in simulation (firmware/nano/sim/nano_sim_test.cpp); aiming
// 7 cycles early centres every off-edge within ±2 cycles (±0.13 µs) of its target.
constexpr uint16_t kEdgeCorrectionTicks = 7;

volatile uint8_t lit_ = 0;
uint16_t t0_;                       // TCNT1 at the on-edge
OffEvent events_[uv::kLedCount];
uint8_t count_ = 0;
volatile uint8_t next_ = 0;
volatile uint16_t wraps_ = 0;       // compare matches still to pass before the armed wake
uint32_t wakeTick_ = 0;             // ticks after the on-edge at which the armed compare fires


// With interrupts off, at about `nowTick` after the on-edge: does every switch-off due soon,
// then arms the compare for the next one.
void service(uint32_t nowTick) {
  while (next_ < count_) {
    const OffEvent& e = events_[next_];
    uint32_t target = e.tick - kEdgeCorrectionTicks;
    if (target - nowTick <= static_cast<uint32_t>(kMarginTicks) + kMinLeadTicks) {
      uint16_t at = static_cast<uint16_t>(t0_ + static_cast<uint16_t>(target));
      uint8_t keep = static_cast<uint8_t>(~(e.mask << LED_SHIFT));  // ready before the wait
      while (static_cast<int16_t>(TCNT1 - at) < 0) {
      }
      LED_PORT &= keep;
      lit_ &= static_cast<uint8_t>(~e.mask);
      nowTick = target;
      next_++;
      continue;
    }
    uint32_t wake = target - kMarginTicks;
    uint32_t delta = wake - nowTick;
    if ((delta & 0xFFFF) < kMinLeadTicks) {  // the first match would be too close to now
      wake -= kMinLeadTicks;
      delta -= kMinLeadTicks;
    }
    wakeTick_ = wake;
    wraps_ = static_cast<uint16_t>(delta >> 16);
    OCR1A = static_cast<uint16_t>(t0_ + static_cast<uint16_t>(wake));
    TIFR1 = _BV(OCF1A);
    TIMSK1 |= _BV(OCIE1A);
    return;
  }
  TIMSK1 &= static_cast<uint8_t>(~_BV(OCIE1A));
}

}  // namespace

void begin() {
  TCCR1A = 0;
  TCCR1B = _BV(CS10);  // normal mode, no prescaler
  TIMSK1 = 0;
}

void fire(const FirePlan& plan) {
  uint8_t sreg = SREG;
  cli();
  count_ = plan.count;
  for (uint8_t i = 0; i < plan.count; i++) events_[i] = plan.events[i];
  next_ = 0;
  uint8_t on = static_cast<uint8_t>(plan.onMask << LED_SHIFT);
  uint8_t port = static_cast<uint8_t>((LED_PORT & ~LED_PORT_MASK) | on);
  t0_ = TCNT1;
  LED_PORT = port;  // every selected LED on in this one write
  lit_ = plan.onMask;
  service(0);
  SREG = sreg;
}

void allOff() {
  uint8_t sreg = SREG;
  cli();
  LED_PORT &= static_cast<uint8_t>(~LED_PORT_MASK);
  lit_ = 0;
  next_ = count_;
  TIMSK1 &= static_cast<uint8_t>(~_BV(OCIE1A));
  SREG = sreg;
}

uint8_t lit() { return lit_; }

bool quietFor(uint16_t ticks) {
  uint8_t sreg = SREG;
  cli();
  bool quiet = compareQuietFor(TIMSK1 & _BV(OCIE1A), wraps_, TIFR1 & _BV(OCF1A), OCR1A, TCNT1, ticks);
  SREG = sreg;
  return quiet;
}

}  // namespace led_timer
}  // namespace nano

ISR(TIMER1_COMPA_vect) {
  using namespace nano::led_timer;
  if (wraps_) {
    wraps_--;
    return;
  }
  service(wakeTick_);
}
