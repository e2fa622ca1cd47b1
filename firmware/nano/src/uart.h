// The Nano's UART (USART0, 8N1, 115200 or a speed raised by `L`) driven from its interrupts, with the arrival time of a `G`
// or a `W`, and every LED off the moment an `R` line ends.
// Arduino's HardwareSerial cannot say when a byte arrived; a scan pass's time 0 is fixed by the
// moment the `\n` of `G` arrives (protocol/nano.md "Scan programs"), so the receive interrupt
// notes it. The two 64-byte rings are HardwareSerial's; its 157 bytes of RAM become 136 here.
#pragma once
#include <stdint.h>

namespace nano {
namespace uart {

constexpr uint8_t kRing = 64;  // a power of two: 8-bit free-running indices

void begin(uint32_t baud);
// The link's speed: at once, or (afterTx) the moment the bytes queued so far have left, stop bit and
// all (the transmit-complete interrupt), so a reply naming the new speed goes out whole at the old.
void setBaud(uint32_t baud, bool afterTx);
int16_t read();  // -1 when nothing waits
bool available();
// Queues all n bytes, or none when they do not fit (a reply is dropped, never waited for).
bool write(const char* data, uint8_t n);
// The Timer1 count and micros() when the receive interrupt took the `\n` of the latest line that
// was just `G` (or `G\r`); false when none arrived since the last call.
bool takeStart(uint16_t& tick, uint32_t& us);
// micros() when the receive interrupt took the `\n` of the latest line that was just `W` (or `W\r`).
uint32_t clockLineUs();
// Whether the receive interrupt switched everything off for an R line (`R` or `R\r`) that found an
// LED lit or an event pending; cleared by the call. The same interrupt returns the speed to 115200.
bool takeResetCut();

}  // namespace uart
}  // namespace nano
