// One I2C master write as the TWI interrupt runs it: what to do at each status the TWI reports
// (ATmega2560 datasheet, "Master Transmitter Mode"). Plain C++, so every status is tested on the host.
#pragma once
#include <stdint.h>

namespace mega {

// TWSR status codes (prescaler bits masked off).
constexpr uint8_t kTwiStart = 0x08, kTwiRepeatedStart = 0x10, kTwiAddressAck = 0x18, kTwiDataAck = 0x28;

struct TwiWrite {
  enum class Action : uint8_t { Send, Stop, Fail };
  uint8_t address;       // 7-bit
  const uint8_t* bytes;  // in RAM, left alone until the write ends
  uint8_t len;
  uint8_t sent;

  // The next step at `status`: Send `byte` (the address byte first), Stop after the last byte was
  // acknowledged, or Fail (no answer, a lost bus, anything unexpected; the caller sends a stop).
  Action step(uint8_t status, uint8_t& byte) {
    switch (status & 0xf8) {
      case kTwiStart:
      case kTwiRepeatedStart:
        sent = 0;
        byte = static_cast<uint8_t>(address << 1);  // write
        return Action::Send;
      case kTwiAddressAck:
      case kTwiDataAck:  // simavr 1.6 reports this one after the address too
        if (sent == len) return Action::Stop;
        byte = bytes[sent++];
        return Action::Send;
      default:
        return Action::Fail;
    }
  }
};

}  // namespace mega
