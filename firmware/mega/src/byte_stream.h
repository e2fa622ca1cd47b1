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
};

}  // namespace mega
