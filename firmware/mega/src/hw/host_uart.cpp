// The host ports' UARTs driven directly from their interrupts.
#include "hw/host_uart.h"

#include <avr/interrupt.h>
#include <avr/io.h>

namespace mega {

namespace {

HostLink* links[4] = {nullptr, nullptr, nullptr, nullptr};

// Each USART's registers sit at the same offsets from its UCSRnA (A, B, C, -, UBRRnL/H, UDRn). The
// base is computed, not looked up: a switch over the three ports became a 20-byte table in RAM.
struct Regs {
  volatile uint8_t *ucsra, *ucsrb, *ucsrc, *udr;
  volatile uint16_t* ubrr;
};
static_assert(&UCSR2A - &UCSR0A == 0x10 && &UDR0 - &UCSR0A == 6 && &UDR3 - &UCSR3A == 6, "the USARTs' register layout");

Regs regs(uint8_t usart) {
  volatile uint8_t* a = usart == 3 ? &UCSR3A : usart == 2 ? &UCSR2A : &UCSR0A;
  return {a, a + 1, a + 2, a + 6, reinterpret_cast<volatile uint16_t*>(a + 4)};
}

inline void rx(uint8_t usart, volatile uint8_t& udr, volatile uint8_t& ucsra) {
  bool bad = ucsra & ((1 << FE0) | (1 << DOR0));  // framing error or overrun: the byte is noise
  char c = static_cast<char>(udr);
  if (links[usart]) links[usart]->received(bad ? '\x01' : c);  // a bad byte fails the line's check (E1)
}

inline void udre(uint8_t usart, volatile uint8_t& udr, volatile uint8_t& ucsrb) {
  int16_t b = links[usart] ? links[usart]->nextTx() : -1;
  if (b < 0) ucsrb &= static_cast<uint8_t>(~(1 << UDRIE0));
  else udr = static_cast<uint8_t>(b);
}

}  // namespace

void HostUart::begin(HostLink& link, uint32_t baud) {
  Regs r = regs(usart_);
  links[usart_] = &link;
  *r.ucsra = (1 << U2X0);
  *r.ubrr = static_cast<uint16_t>((F_CPU / 4 / baud - 1) / 2);  // as Arduino rounds it: 16 at 115200
  *r.ucsrc = (1 << UCSZ01) | (1 << UCSZ00);                      // 8N1
  *r.ucsrb = (1 << RXEN0) | (1 << TXEN0) | (1 << RXCIE0);
}

void HostUart::kick() {
  Regs r = regs(usart_);
  *r.ucsrb |= (1 << UDRIE0);
}

}  // namespace mega

ISR(USART0_RX_vect) { mega::rx(0, UDR0, UCSR0A); }
ISR(USART0_UDRE_vect) { mega::udre(0, UDR0, UCSR0B); }
ISR(USART2_RX_vect) { mega::rx(2, UDR2, UCSR2A); }
ISR(USART2_UDRE_vect) { mega::udre(2, UDR2, UCSR2B); }
ISR(USART3_RX_vect) { mega::rx(3, UDR3, UCSR3A); }
ISR(USART3_UDRE_vect) { mega::udre(3, UDR3, UCSR3B); }
