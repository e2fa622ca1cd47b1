// USART1 for the Nano: the receive interrupt appends to one ring, the transmit interrupt drains the
// other. One writer and one reader per ring, 8-bit free-running indices: no interrupts turned off.
#include "hw/nano_uart.h"

#include <Arduino.h>
#include <avr/interrupt.h>
#include <avr/io.h>

namespace mega {

namespace {

struct Ring {
  char buf[NanoUart::kRing];
  volatile uint8_t in, out;  // free-running; slot = index % kRing
  uint8_t used() const { return static_cast<uint8_t>(in - out); }
};
static_assert((NanoUart::kRing & (NanoUart::kRing - 1)) == 0, "free-running 8-bit indices: the ring must divide 256");

Ring rx, tx;
volatile bool markNewline = false;  // the newline of a G or W goes out next, before the ring

// Every write to UDR1 clears TXC1 (by writing it 1, U2X1 kept), so TXC1 set means the transmitter
// has been idle since its last byte's stop bit. With interrupts off.
inline void transmit(char c) {
  UDR1 = static_cast<uint8_t>(c);
  UCSR1A = (1 << U2X1) | (1 << TXC1);
}

// "op\n" now if the transmitter is idle (TXC1: not even a byte still shifting out); interrupts off.
bool sendNow(char op) {
  if (tx.used() || markNewline || !(UCSR1A & (1 << TXC1))) return false;
  transmit(op);
  markNewline = true;
  UCSR1B |= 1 << UDRIE1;
  return true;
}

}  // namespace

bool nanoUartSendMark() { return sendNow('G'); }

bool NanoUart::writeNow(char op, uint32_t& atUs) {
  uint8_t sreg = SREG;
  cli();
  bool sent = sendNow(op);
  if (sent) atUs = micros();  // Arduino's micros() is right with interrupts off
  SREG = sreg;
  return sent;
}

// As Arduino rounds it with U2X: 16 at 115200, 7 at 250000 (exact).
static uint16_t ubrrFor(uint32_t baud) { return static_cast<uint16_t>((F_CPU / 4 / baud - 1) / 2); }

bool NanoUart::setBaud(uint32_t baud) {
  uint8_t sreg = SREG;
  cli();
  bool idle = !tx.used() && !markNewline && (UCSR1A & (1 << TXC1));
  if (idle) UBRR1 = ubrrFor(baud);
  SREG = sreg;
  return idle;
}

void NanoUart::begin(uint32_t baud) {
  UCSR1A = 1 << U2X1;
  UBRR1 = ubrrFor(baud);
  UCSR1C = (1 << UCSZ11) | (1 << UCSZ10);                      // 8N1
  UCSR1B = (1 << RXEN1) | (1 << TXEN1) | (1 << RXCIE1);
}

int16_t NanoUart::read() {
  if (!rx.used()) return -1;
  uint8_t c = static_cast<uint8_t>(rx.buf[rx.out % kRing]);
  rx.out = static_cast<uint8_t>(rx.out + 1);
  return c;
}

bool NanoUart::write(const char* data, uint8_t n) {
  if (n > kRing - tx.used()) return false;
  uint8_t in = tx.in;
  for (uint8_t i = 0; i < n; i++) tx.buf[in++ % kRing] = data[i];
  tx.in = in;
  UCSR1B |= 1 << UDRIE1;
  return true;
}

}  // namespace mega

using mega::markNewline;
using mega::transmit;
using mega::rx;
using mega::tx;
using mega::NanoUart;

ISR(USART1_RX_vect) {
  bool bad = UCSR1A & ((1 << FE1) | (1 << DOR1));
  char c = static_cast<char>(UDR1);
  if (rx.used() == NanoUart::kRing) return;  // full: the line it belongs to fails its checks
  rx.buf[rx.in % NanoUart::kRing] = bad ? '\x01' : c;  // noise: the reply will not parse
  rx.in = static_cast<uint8_t>(rx.in + 1);
}

ISR(USART1_UDRE_vect) {
  if (markNewline) {
    transmit('\n');
    markNewline = false;
    return;
  }
  if (tx.out == tx.in) {
    UCSR1B &= static_cast<uint8_t>(~(1 << UDRIE1));
    return;
  }
  transmit(tx.buf[tx.out % NanoUart::kRing]);
  tx.out = static_cast<uint8_t>(tx.out + 1);
}
