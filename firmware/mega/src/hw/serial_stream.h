// Arduino's HardwareSerial as a ByteStream: reads what has arrived, writes only what fits the
// transmit buffer, so no caller ever waits for the UART.
#pragma once
#include <Arduino.h>

#include "byte_stream.h"

namespace mega {

class SerialStream : public ByteStream {
 public:
  explicit SerialStream(HardwareSerial& port) : port_(port) {}
  int16_t read() override { return static_cast<int16_t>(port_.read()); }
  bool write(const char* data, uint8_t n) override {
    if (port_.availableForWrite() < n) return false;
    port_.write(reinterpret_cast<const uint8_t*>(data), n);
    return true;
  }

 private:
  HardwareSerial& port_;
};

}  // namespace mega

