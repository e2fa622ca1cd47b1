// A serial port as the Mega's logic sees it: bytes in, whole writes out or none (never waits).
// hw/nano_uart is the Nano's UART; host tests use in-memory fakes.
#pragma once
#include <stdint.h>

namespace mega {

class ByteStream {
 public:
  // The next received byte, or -1.
  virtual int16_t read() = 0;
  // Writes all n bytes if the transmit buffer has room for them, else nothing; never waits.
  virtual bool write(const char* data, uint8_t n) = 0;
  // Sends `op` and a newline at once, when nothing else is going out (the transmitter idle), and
  // gives the micros() at which `op` went into the transmitter; false, sending nothing, when busy.
  // The printhead link times its `W` by it (nano_clock.h).
  virtual bool writeNow(char op, uint32_t& atUs) = 0;
  // The port's speed, changed now if nothing is going out (the transmitter idle, the last stop bit
  // gone); false, changing nothing, while something is (protocol/nano.md "Link speed").
  virtual bool setBaud(uint32_t baud) = 0;
};

}  // namespace mega
