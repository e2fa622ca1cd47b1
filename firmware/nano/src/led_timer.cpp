// Exposure timing on Timer1 compare A: each event sets the LEDs' state at its own tick, ±0.5 µs.
//
// Why it wakes early and spins: the compare interrupt can be held up by another interrupt
// (UART, ADC, Timer0, servo: each under 6 µs). So the compare is set kMarginTicks before an event,
// and the handler waits on TCNT1 for the exact tick, with interrupts on until kQuietTicks before it
// and off for the rest. The edge then lands within one pass of the wait loop (8 cycles) of the
// target, whatever else is running, and no stretch with interrupts off grows past a few events'
// worth however dense a program is. Timer1 counts at the CPU clock and wraps every 4.096 ms;
// longer gaps count compare matches (`wraps_`) until the last one.
//
// Events come one at a time, each relative to the one before it (its ideal tick is the new
// anchor, so rounding never accumulates): from an F's plan, or from a scan program's store.
#include "led_timer.h"

#include <avr/interrupt.h>
#include <avr/io.h>

#include "compare_wake.h"
#include "pins.h"

namespace nano {
namespace led_timer {
namespace {

constexpr uint16_t kMarginTicks = 512;   // wake 32 µs before an event
constexpr uint16_t kMinLeadTicks = 256;  // never arm a compare closer than 16 µs ahead
// Interrupts off for the last 24 µs of a wait: the UART's two, Timer0's and the ADC's handlers can
// run back to back just before it (about 5 µs each), and must all be done before the edge.
constexpr uint16_t kQuietTicks = 384;
// The wait loop leaves 5-9 cycles after the target tick (one 8-cycle pass of the loop plus the
// port write), measured on the pins in simulation (firmware/nano/test/sim/nano_sim_test.cpp); aiming
// 7 cycles early centres every edge within ±2 cycles (±0.13 µs) of its target.
constexpr uint16_t kEdgeCorrectionTicks = 7;

volatile uint8_t lit_ = 0;
uint16_t anchor_;           // TCNT1 at the ideal tick of the last event (or of time 0)
volatile bool pending_ = false;  // an event waits: pendTick_ after the anchor, setting pendMask_
uint32_t pendTick_;
uint8_t pendMask_;
// The source: a scan program's store, or else an F's offs.
ScanStore* store_ = nullptr;
OffEvent events_[uv::kLedCount];
uint8_t count_ = 0, next_ = 0;
uint32_t lastOff_;          // tick of the F's last off, after its on-edge
volatile uint16_t wraps_ = 0;  // compare matches still to pass before the armed wake
uint32_t wakeTick_ = 0;        // ticks after the anchor at which the armed compare fires
volatile bool spinning_ = false;  // waiting, interrupts on, for the pending event's tick
// A run cut by allOff(): when, for the dose records (takeCut).
bool cut_ = false;
int32_t cutTicks_ = 0;

// Ticks since the anchor at TCNT1 `now`, with interrupts off, while a run is pending: from the pending event
// while the timer spins for it, else from the armed compare (its wraps still to pass, and a match
// not yet served). Only a cut asks, so the edges pay nothing for it.
int32_t sinceAnchor(uint16_t now) {
  if (spinning_) return static_cast<int32_t>(pendTick_) - static_cast<int16_t>(static_cast<uint16_t>(anchor_ + static_cast<uint16_t>(pendTick_)) - now);
  uint32_t left = static_cast<uint32_t>(wraps_) << 16;
  if (TIFR1 & _BV(OCF1A)) left -= static_cast<uint16_t>(now - OCR1A);
  else left += static_cast<uint16_t>(OCR1A - now);
  return static_cast<int32_t>(wakeTick_ - left);
}

// fetch() without its hot path: a scan program's end (the chain's next program, or the end of the
// chain), an F's offs, or the end of the run with every LED off.
__attribute__((noinline)) bool fetchRest() {
  if (store_) {
    uint32_t d;
    uint8_t m;
    if (store_->next(d, m) == ScanStore::Step::Event) {
      pendTick_ = d * kTicksPerUs;
      pendMask_ = m;
      return true;
    }
  } else if (next_ < count_) {
    const OffEvent& e = events_[next_++];
    pendTick_ = e.tick - lastOff_;
    lastOff_ = e.tick;
    pendMask_ = static_cast<uint8_t>(pendMask_ & ~e.mask);
    return true;
  }
  LED_PORT &= static_cast<uint8_t>(~LED_PORT_MASK);  // the end of a chain, or one cut short
  lit_ = 0;
  store_ = nullptr;
  return false;
}

// Loads the next event, or ends the run with every LED off. The next event of a running scan
// program is read inline, between two edges that may be microseconds apart; the rest is a call.
static_assert(kTicksPerUs == 16, "ScanStore::ticks converts µs to ticks by a 4-bit shift");
inline bool fetch() {
  uint32_t w;
  if (store_ && store_->take(w)) {
    pendTick_ = ScanStore::ticks(w);
    pendMask_ = ScanStore::lights(w);
    return true;
  }
  return fetchRest();
}

// With interrupts off, at about `nowTick` after the anchor (modulo 2³², so it may be before it):
// does every event due soon, then arms the compare for the next one.
void service(uint32_t nowTick) {
  while (pending_) {
    // `nowTick` is where the caller expects the counter to be; a compare interrupt held up by a
    // long interrupts-off stretch runs later than that. Arming from the expected tick would then
    // set a compare the counter has already passed, and the event would wait a whole 4.096 ms wrap
    // (seen on the real images in the Mega's scan test: chains shifted 4 and 8 ms). So the low 16
    // bits come from TCNT1 itself; the caller is never off by half a wrap.
    nowTick += static_cast<uint32_t>(static_cast<int32_t>(static_cast<int16_t>(static_cast<uint16_t>(TCNT1 - anchor_) - static_cast<uint16_t>(nowTick))));
    uint32_t target = pendTick_ - kEdgeCorrectionTicks;
    // Due soon, or already due (an interrupt held up past it): done now, by the wait below.
    if (static_cast<int32_t>(target - nowTick) <= static_cast<int32_t>(kMarginTicks) + kMinLeadTicks) {
      uint16_t near = static_cast<uint16_t>(target);
      for (;;) {
        uint16_t at = static_cast<uint16_t>(anchor_ + near);
        uint16_t quiet = static_cast<uint16_t>(at - kQuietTicks);
        if (static_cast<int16_t>(TCNT1 - quiet) < 0) {
          spinning_ = true;
          sei();  // other interrupts may run until the last stretch
          while (static_cast<int16_t>(TCNT1 - quiet) < 0) {
          }
          cli();
          spinning_ = false;
          if (!pending_) return;  // an R arrived meanwhile: allOff() has ended the run
        }
        uint8_t on = static_cast<uint8_t>(pendMask_ << LED_SHIFT);
        while (static_cast<int16_t>(TCNT1 - at) < 0) {
        }
        LED_PORT = static_cast<uint8_t>((LED_PORT & ~LED_PORT_MASK) | on);
        lit_ = pendMask_;
        anchor_ = static_cast<uint16_t>(anchor_ + static_cast<uint16_t>(pendTick_));
        pending_ = fetch();
        // An event this close to the edge just made is due soon whatever the counter says: straight
        // to its wait, without the 32-bit reckoning above (events a few µs apart, as a scan's
        // LEDs give where their gains differ, came 10 µs late with it; nano_scan_sim_test).
        if (!pending_ || pendTick_ >= kMarginTicks + kMinLeadTicks) break;
        near = static_cast<uint16_t>(static_cast<uint16_t>(pendTick_) - kEdgeCorrectionTicks);
      }
      nowTick = static_cast<uint32_t>(0) - kEdgeCorrectionTicks;
      continue;
    }
    uint32_t wake = target - kMarginTicks;
    uint32_t delta = wake - nowTick;
    if ((delta & 0xFFFF) < kMinLeadTicks) {  // the first match would be too close to now
      wake -= kMinLeadTicks;
      delta -= kMinLeadTicks;
    }
    if (static_cast<uint16_t>(anchor_ + static_cast<uint16_t>(wake)) < 2) {
      // simavr's Timer1 let a compare armed at 1 go by until the next wrap (seen in
      // nano_scan_sim_test: the wake came 4.096 ms late), so 0 and 1 are never armed; waking
      // 16 µs earlier costs nothing on the chip, and keeps the simulation the measure of it.
      wake -= kMinLeadTicks;
      delta -= kMinLeadTicks;
    }
    wakeTick_ = wake;
    wraps_ = static_cast<uint16_t>(delta >> 16);
    OCR1A = static_cast<uint16_t>(anchor_ + static_cast<uint16_t>(wake));
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
  store_ = nullptr;
  count_ = plan.count;
  for (uint8_t i = 0; i < plan.count; i++) events_[i] = plan.events[i];
  next_ = 0;
  lastOff_ = 0;
  pendMask_ = plan.onMask;
  pending_ = fetch();  // the first off, ready before the on-edge: it may be due 1 µs after it
  uint8_t on = static_cast<uint8_t>(plan.onMask << LED_SHIFT);
  uint8_t port = static_cast<uint8_t>((LED_PORT & ~LED_PORT_MASK) | on);
  anchor_ = TCNT1;
  LED_PORT = port;  // every selected LED on in this one write
  lit_ = plan.onMask;
  service(0);
  SREG = sreg;
}

void run(ScanStore& store, uint16_t time0) {
  uint8_t sreg = SREG;
  cli();
  store_ = &store;
  anchor_ = time0;
  pending_ = fetch();
  service(static_cast<uint32_t>(static_cast<int32_t>(static_cast<int16_t>(TCNT1 - time0))));
  SREG = sreg;
}

bool allOff() {
  uint8_t sreg = SREG;
  cli();
  LED_PORT &= static_cast<uint8_t>(~LED_PORT_MASK);
  uint16_t now = TCNT1;  // the moment of the cut, read right behind the write
  if (pending_) {  // a run cut short: an F's time since its on-edge, a chain's since its last event
    // (lastOff_ is the pending off's tick: the anchor, the last edge made, is pendTick_ before it)
    cutTicks_ = (store_ ? 0 : static_cast<int32_t>(lastOff_ - pendTick_)) + sinceAnchor(now);
    cut_ = true;
  }
  bool was = lit_ || pending_;
  lit_ = 0;
  pending_ = false;
  store_ = nullptr;
  TIMSK1 &= static_cast<uint8_t>(~_BV(OCIE1A));
  SREG = sreg;
  return was;
}

uint8_t lit() { return lit_; }

bool takeCut(int32_t& ticks) {
  uint8_t sreg = SREG;
  cli();
  bool was = cut_;
  ticks = cutTicks_;
  cut_ = false;
  SREG = sreg;
  return was;
}

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
