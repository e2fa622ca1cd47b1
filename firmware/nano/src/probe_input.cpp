// CR Touch trigger on D7: its level, plus any short trigger pulse latched by a pin-change interrupt.
#include "probe_input.h"

#include <avr/interrupt.h>
#include <avr/io.h>

#include "pins.h"

namespace nano {
namespace probe_input {
namespace {
volatile bool latched_ = false;
}

void begin() {
  PROBE_PCMSK |= _BV(PROBE_PCINT);
  PCICR |= _BV(PROBE_PCIE);
}

bool takeTriggered() {
  uint8_t sreg = SREG;
  cli();
  bool t = latched_ || (PROBE_PIN & _BV(PROBE_BIT));
  latched_ = false;
  SREG = sreg;
  return t;
}

}  // namespace probe_input
}  // namespace nano

ISR(PROBE_vect) {
  if (PROBE_PIN & _BV(PROBE_BIT)) nano::probe_input::latched_ = true;
}
