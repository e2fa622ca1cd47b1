// One WS2812 NeoPixel on D8: writes a colour as 24 cycle-timed bits (about 32 µs, interrupts off).
//
// Why not Adafruit_NeoPixel: it can't be installed on our build machines, so the image measured
// here could not include it. It would also do the same thing: a cli() bit-bang of the whole
// strip. This sends one pixel with sbi/cbi, which touch only PB0 and never the LED bits that
// share PORTB. main.cpp calls it only when no LED switch-off or servo edge is due within 62 µs.
//
// Bit timing at 16 MHz (WS2812B: T0H 250-550 ns, T1H 650-950 ns, period about 1.25 µs):
// high for 7 cycles (437 ns) for a 0, 13 cycles (812 ns) for a 1; 20-21 cycles a bit.
#include "neopixel.h"

#include <avr/interrupt.h>
#include <avr/io.h>

#include "pins.h"

namespace nano {
namespace neopixel {
namespace {

inline void sendByte(uint8_t byte) {
  uint8_t bits = 8;
  asm volatile(
      "1:                 \n\t"
      "sbi  %[port], %[bit] \n\t"  // 0: high
      "nop                \n\t"
      "nop                \n\t"
      "nop                \n\t"
      "nop                \n\t"
      "sbrs %[data], 7    \n\t"  // 6: a 1 skips the early low
      "cbi  %[port], %[bit] \n\t"  // 7: low for a 0
      "lsl  %[data]       \n\t"
      "nop                \n\t"
      "nop                \n\t"
      "nop                \n\t"
      "nop                \n\t"
      "cbi  %[port], %[bit] \n\t"  // 13: low for a 1
      "nop                \n\t"
      "nop                \n\t"
      "dec  %[bits]       \n\t"
      "brne 1b            \n\t"
      : [data] "+r"(byte), [bits] "+r"(bits)
      : [port] "I"(_SFR_IO_ADDR(PIXEL_PORT)), [bit] "I"(PIXEL_BIT));
}

}  // namespace

void begin() {
  PIXEL_PORT &= static_cast<uint8_t>(~_BV(PIXEL_BIT));
  PIXEL_DDR |= _BV(PIXEL_BIT);
}

void show(uint8_t r, uint8_t g, uint8_t b) {
  uint8_t sreg = SREG;
  cli();
  sendByte(g);  // WS2812 order: green, red, blue
  sendByte(r);
  sendByte(b);
  SREG = sreg;
}

}  // namespace neopixel
}  // namespace nano
