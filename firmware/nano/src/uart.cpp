// USART0 for the Mega link: the receive interrupt appends to one ring, notes when a `G` line ends
// and switches the LEDs off when an `R` line does; the transmit interrupt drains the other ring.
// One writer and one reader per ring.
#include "uart.h"

#include "led_timer.h"
#include "nano_codec.h"

#include <Arduino.h>
#include <avr/interrupt.h>
#include <avr/io.h>

namespace nano {
namespace uart {
namespace {

struct Ring {
  char buf[kRing];
  volatile uint8_t in, out;  // free-running; slot = index % kRing
  uint8_t used() const { return static_cast<uint8_t>(in - out); }
};
static_assert((kRing & (kRing - 1)) == 0, "free-running 8-bit indices: the ring must divide 256");

Ring rx, tx;
// Where the receiver is in a line that is just `G`, `R` or `W`, as the line splitter reads it: 1 at a
// line start, the letter after it, the letter in lower case after its one `\r`, 0 elsewhere.
uint8_t shortLine = 1;
volatile bool started = false;
volatile uint16_t startTick;
volatile uint32_t startUs;
volatile uint32_t clockUs;  // the latest W's, apart from the G's: a G may follow a W before it is answered
volatile bool resetCut = false;
volatile uint8_t nextUbrr;  // the divisor the transmit-complete interrupt sets (16 at most)

// As Arduino rounds it with U2X: 16 at 115200 (2.1 % fast), 7, 3 and 1 at 250000, 500000 and
// 1000000 (exact).
constexpr uint16_t ubrrFor(uint32_t baud) { return static_cast<uint16_t>((F_CPU / 4 / baud - 1) / 2); }
constexpr uint16_t kStartUbrr = ubrrFor(uv::kNanoBaud);

}  // namespace

void begin(uint32_t baud) {
  UCSR0A = 1 << U2X0;
  UBRR0 = ubrrFor(baud);
  UCSR0C = (1 << UCSZ01) | (1 << UCSZ00);  // 8N1
  UCSR0B = (1 << RXEN0) | (1 << TXEN0) | (1 << RXCIE0);
}

void setBaud(uint32_t baud, bool afterTx) {
  uint8_t ubrr = static_cast<uint8_t>(ubrrFor(baud));
  uint8_t sreg = SREG;
  cli();
  if (afterTx && (tx.used() || !(UCSR0A & (1 << UDRE0)) || !(UCSR0A & (1 << TXC0)))) {
    nextUbrr = ubrr;  // something is still going out: change once it all has
    UCSR0B |= 1 << TXCIE0;
  } else {
    UCSR0B &= static_cast<uint8_t>(~(1 << TXCIE0));
    UBRR0 = ubrr;
  }
  SREG = sreg;
}

int16_t read() {
  if (!rx.used()) return -1;
  uint8_t c = static_cast<uint8_t>(rx.buf[rx.out % kRing]);
  rx.out = static_cast<uint8_t>(rx.out + 1);
  return c;
}

bool available() { return rx.used() != 0; }

bool write(const char* data, uint8_t n) {
  if (n > kRing - tx.used()) return false;
  if (n && tx.used() == 0 && (UCSR0A & (1 << UDRE0))) {  // idle: the first byte goes out now
    UDR0 = static_cast<uint8_t>(*data++);
    UCSR0A = (1 << U2X0) | (1 << TXC0);  // TXC0 clears by a 1: set again once this has all gone
    n--;
  }
  uint8_t in = tx.in;
  for (uint8_t i = 0; i < n; i++) tx.buf[in++ % kRing] = data[i];
  tx.in = in;
  if (n) UCSR0B |= 1 << UDRIE0;
  return true;
}

bool takeResetCut() {
  uint8_t sreg = SREG;
  cli();
  bool cut = resetCut;
  resetCut = false;
  SREG = sreg;
  return cut;
}

uint32_t clockLineUs() {
  uint8_t sreg = SREG;
  cli();
  uint32_t us = clockUs;
  SREG = sreg;
  return us;
}

bool takeStart(uint16_t& tick, uint32_t& us) {
  uint8_t sreg = SREG;
  cli();
  bool got = started;
  tick = startTick;
  us = startUs;
  started = false;
  SREG = sreg;
  return got;
}

}  // namespace uart
}  // namespace nano

using nano::uart::rx;

ISR(USART_RX_vect) {
  uint16_t tick = TCNT1;  // first: the start mark is timed from here
  using namespace nano::uart;
  bool bad = UCSR0A & ((1 << FE0) | (1 << DOR0));
  char c = static_cast<char>(UDR0);
  // Never a silently shortened line: the last free slot takes a mark in place of the byte that
  // does not fit, so the line that lost bytes is malformed (a line lost whole never runs at all).
  // Noise, too, makes its line malformed. The G and R patterns read what the splitter will read.
  // Above 115200 a byte no line holds is a doubt about the speed (protocol/nano.md "Link speed"):
  // back to 115200 and every LED off here, before the next byte; the main loop does the rest by the mark.
  if (UBRR0L != kStartUbrr && (bad || (static_cast<uint8_t>(c) < 0x20 && c != '\n' && c != '\r') || static_cast<uint8_t>(c) > 0x7E)) {
    if (nano::led_timer::allOff()) resetCut = true;
    UCSR0B &= static_cast<uint8_t>(~(1 << TXCIE0));
    UBRR0 = kStartUbrr;
    bad = true;
  }
  uint8_t used = rx.used();
  if (bad || used >= kRing - 1) c = '\x01';
  if (used < kRing) {
    rx.buf[rx.in % kRing] = c;
    rx.in = static_cast<uint8_t>(rx.in + 1);
  }
  if (c == '\n') {
    if (shortLine == 'G' || shortLine == 'g') {
      startTick = tick;
      startUs = micros();
      started = true;
    } else if (shortLine == 'W' || shortLine == 'w') {
      clockUs = micros();
    } else if (shortLine == 'R' || shortLine == 'r') {
      if (nano::led_timer::allOff()) resetCut = true;  // the main loop's R handler does the rest
      UCSR0B &= static_cast<uint8_t>(~(1 << TXCIE0));  // and back to 115200 (protocol/nano.md "Link speed")
      UBRR0 = kStartUbrr;
    }
    shortLine = 1;
  } else if (shortLine == 1 && (c == 'G' || c == 'R' || c == 'W')) {
    shortLine = static_cast<uint8_t>(c);
  } else if ((shortLine == 'G' || shortLine == 'R' || shortLine == 'W') && c == '\r') {
    shortLine = static_cast<uint8_t>(shortLine | 0x20);  // its one carriage return: g, r or w
  } else {
    shortLine = 0;
  }
}

ISR(USART_UDRE_vect) {
  using namespace nano::uart;
  if (tx.out == tx.in) {
    UCSR0B &= static_cast<uint8_t>(~(1 << UDRIE0));
    return;
  }
  UDR0 = static_cast<uint8_t>(tx.buf[tx.out % kRing]);
  UCSR0A = (1 << U2X0) | (1 << TXC0);
  tx.out = static_cast<uint8_t>(tx.out + 1);
}

// The last byte queued before a speed change has left, stop bit and all: the new divisor.
ISR(USART_TX_vect) {
  using namespace nano::uart;
  if (tx.used()) return;  // more was queued since (not by the protocol): wait for that too
  UBRR0 = nextUbrr;
  UCSR0B &= static_cast<uint8_t>(~(1 << TXCIE0));
}
