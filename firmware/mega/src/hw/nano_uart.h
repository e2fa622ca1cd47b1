// The printhead Nano's UART (USART1, D18/D19) driven from its interrupts, as the ByteStream the
// printhead link reads and writes. Arduino's HardwareSerial did this job for 157 bytes of RAM and an
// 18-byte vtable; the same two 64-byte rings cost 130 here.
#pragma once
#include <stdint.h>

#include "byte_stream.h"

namespace mega {

class NanoUart : public ByteStream {
 public:
  // A power of two. The longest line out (64 bytes with its newline) fits whole; in, the longest
  // reply (43 bytes) twice over, for main-loop passes up to 5 ms (a byte takes 87 us).
  static constexpr uint8_t kRing = 64;

  void begin(uint32_t baud);
  int16_t read() override;
  bool write(const char* data, uint8_t n) override;
};

}  // namespace mega
