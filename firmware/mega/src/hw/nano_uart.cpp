// USART1 for the Nano: the receive interrupt appends to one ring, the transmit interrupt drains the
// other. One writer and one reader per ring, 8-bit free-running indices: no interrupts turned off.
#include "hw/nano_uart.h"

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
volatile bool markNewline = false;  // the G's newline goes out next, before the ring

}  // namespace

bool nanoUartSendMark() {
  if (tx.used() || markNewline || !(UCSR1A & (1 << UDRE1))) return false;
  UDR1 = 'G';
  markNewline = true;
  UCSR1B |= 1 << UDRIE1;
  return true;
}

void NanoUart::begin(uint32_t baud) {
  UCSR1A = 1 << U2X1;
  UBRR1 = static_cast<uint16_t>((F_CPU / 4 / baud - 1) / 2);  // as Arduino rounds it: 16 at 115200
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
    UDR1 = '\n';
    markNewline = false;
    return;
  }
  if (tx.out == tx.in) {
    UCSR1B &= static_cast<uint8_t>(~(1 << UDRIE1));
    return;
  }
  UDR1 = static_cast<uint8_t>(tx.buf[tx.out % NanoUart::kRing]);
  tx.out = static_cast<uint8_t>(tx.out + 1);
}
