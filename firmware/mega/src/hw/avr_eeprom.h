// The ATmega2560's EEPROM behind the Eeprom interface: a write is started and left to finish.
#pragma once
#include <avr/eeprom.h>

#include "eeprom.h"

namespace mega {

class AvrEeprom : public Eeprom {
 public:
  uint8_t read(uint16_t addr) override { return eeprom_read_byte(reinterpret_cast<const uint8_t*>(addr)); }
  bool ready() override { return eeprom_is_ready(); }
  // avr-libc waits only for a write still in progress, which ready() has ruled out.
  void write(uint16_t addr, uint8_t value) override { eeprom_write_byte(reinterpret_cast<uint8_t*>(addr), value); }
};

}  // namespace mega
