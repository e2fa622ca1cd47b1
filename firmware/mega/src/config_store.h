// Where the settings live: CONFIG.TXT on SD for people, a CRC-checked copy in EEPROM for a
// machine without a card (firmware/mega/CONFIG.md).
#pragma once
#include <stdint.h>

#include "config.h"
#include "eeprom.h"
#include "storage.h"

namespace mega {

constexpr const char* kConfigFile = "CONFIG.TXT";

class ConfigStore {
 public:
  enum Source : uint8_t { kFromDefaults = 0, kFromEeprom = 1, kFromFile = 2 };

  ConfigStore(Config& config, Storage& sd, Eeprom& eeprom) : c_(config), sd_(sd), ee_(eeprom) {}

  // The defaults, then the EEPROM copy if it is intact, then every good line of CONFIG.TXT.
  // Returns the kFrom* bits of what was read.
  uint8_t load();
  // Writes CONFIG.TXT (if there is a card) and starts the EEPROM copy, which poll() writes a
  // byte at a time so the main loop never waits the 3.4 ms a byte takes. Returns 0, or 22
  // (file_error) if the card refused the file; the EEPROM copy is made either way.
  uint8_t save();
  // Writes the next changed EEPROM byte if the EEPROM is free; never waits.
  void poll();
  // An EEPROM copy is still being written: the settings must not change until it is done.
  bool saving() const { return next_ < kImageSize; }

  static constexpr uint16_t kImageSize = 4 + 4 * kKeyCount + 4;  // magic, version, count; values; CRC-32

 private:
  uint8_t imageByte(uint16_t i) const;
  bool loadEeprom();
  bool loadFile();
  bool writeFile();

  Config& c_;
  Storage& sd_;
  Eeprom& ee_;
  uint32_t crc_ = 0;
  uint16_t next_ = kImageSize;
};

}  // namespace mega
