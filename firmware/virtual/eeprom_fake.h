// Host tests' EEPROM: 4 KB of bytes where each write keeps the EEPROM busy for a number of polls.
#pragma once
#include <stdint.h>
#include <string.h>

#include "eeprom.h"

namespace mega {

class FakeEeprom : public Eeprom {
 public:
  FakeEeprom() { memset(bytes, 0xff, sizeof bytes); }
  uint8_t read(uint16_t addr) override { return bytes[addr]; }
  bool ready() override {
    if (busy_ == 0) return true;
    busy_--;
    return false;
  }
  void write(uint16_t addr, uint8_t value) override {
    bytes[addr] = value;
    writes++;
    busy_ = busyPolls;
  }

  uint8_t bytes[4096];
  uint32_t writes = 0;
  uint8_t busyPolls = 2;  // how many ready() calls a write stays busy for

 private:
  uint8_t busy_ = 0;
};

}  // namespace mega
