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
  bool writeNow(char op, uint32_t& atUs) override;
  bool setBaud(uint32_t baud) override;
};

// For the step interrupt only: a scan pass's G (protocol/nano.md "Scan programs"), "G\n" now, when
// the transmitter is idle, so its newline reaches the Nano two byte-times from now. The 'G' goes
// straight into UDR1 and the newline follows from the transmit interrupt ahead of the ring, so a
// line the main loop is writing meanwhile cannot split it. False when the line is busy.
bool nanoUartSendMark();

}  // namespace mega
