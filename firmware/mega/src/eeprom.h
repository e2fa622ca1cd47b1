// The EEPROM as the config store sees it: bytes that are read at once and written one at a time,
// each write taking about 3.4 ms in the background (hw/avr_eeprom on the board, a fake on the host).
#pragma once
#include <stdint.h>

namespace mega {

class Eeprom {
 public:
  virtual uint8_t read(uint16_t addr) = 0;
  // No write is in progress, so read() and write() return at once.
  virtual bool ready() = 0;
  // Starts writing one byte; only when ready().
  virtual void write(uint16_t addr, uint8_t value) = 0;
};

}  // namespace mega
