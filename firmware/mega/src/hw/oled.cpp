// The SSD1306 on the TWI: the main loop starts a frame when the bus is free, the interrupt sends it.
#include "hw/oled.h"

#include <Arduino.h>
#include <avr/interrupt.h>
#include <avr/io.h>

#include "pins.h"
#include "twi_write.h"

namespace mega {

namespace {

constexpr uint32_t kTwiHz = 400000;
// A frame takes about 0.5 ms on the wire; one not finished after this hung the bus (a panel holding
// SCL, a glitch): the TWI is reset and the panel set up again after kPanelRetryMs.
constexpr uint32_t kFrameTimeoutMs = 20;

PanelFrame frame;     // the interrupt reads it while busy; the main loop writes it only when idle
TwiWrite transfer = {};
volatile bool busy = false, refused = false;

}  // namespace

ISR(TWI_vect) {
  uint8_t byte = 0;
  switch (transfer.step(TWSR, byte)) {
    case TwiWrite::Action::Send:
      TWDR = byte;
      TWCR = _BV(TWINT) | _BV(TWEN) | _BV(TWIE);
      break;
    case TwiWrite::Action::Fail:
      refused = true;
      // fall through - release the bus either way
    case TwiWrite::Action::Stop:
      TWCR = _BV(TWINT) | _BV(TWEN) | _BV(TWSTO);
      busy = false;
      break;
  }
}

void Oled::begin() {
  pinMode(PIN_PANEL_SDA, INPUT_PULLUP);  // the module's own pull-ups do the real work; these hold the
  pinMode(PIN_PANEL_SCL, INPUT_PULLUP);  // lines high without a panel, so a start cannot hang
  TWSR = 0;                                                 // prescaler 1
  TWBR = static_cast<uint8_t>((F_CPU / kTwiHz - 16) / 2);  // 12: 400 kHz
  TWCR = _BV(TWEN);
  panel_.begin();
}

void Oled::poll(uint32_t nowMs) {
  if (busy) {
    if (nowMs - startedMs_ <= kFrameTimeoutMs) return;
    TWCR = 0;  // let go of the bus; the next start enables the TWI again
    busy = false;
    panel_.failed(nowMs);
    return;
  }
  if (refused) {
    refused = false;
    panel_.failed(nowMs);
    return;
  }
  if (TWCR & _BV(TWSTO)) return;  // the last stop is still on the wire
  if (!panel_.next(frame, nowMs)) return;
  transfer = {kPanelAddress, frame.bytes, frame.len, 0};
  startedMs_ = nowMs;
  busy = true;
  asm volatile("" ::: "memory");  // the frame is in place before the interrupt can run
  TWCR = _BV(TWINT) | _BV(TWEN) | _BV(TWIE) | _BV(TWSTA);
}

}  // namespace mega
