// The host ports' UARTs (USART0 = USB, USART2 or USART3 = ESP) driven directly: the receive
// interrupt puts each byte into its HostLink's line ring and the transmit interrupt empties its
// transmit ring. Arduino's HardwareSerial objects for these ports are not linked at all, which
// saves their 64-byte buffers and a copy of every byte.
#pragma once
#include <stdint.h>

#include "host_link.h"

namespace mega {

class HostUart : public TxPort {
 public:
  // usart: 0, 2 or 3.
  explicit HostUart(uint8_t usart) : usart_(usart) {}
  void begin(HostLink& link, uint32_t baud);
  void kick() override;

 private:
  uint8_t usart_;
};

}  // namespace mega
