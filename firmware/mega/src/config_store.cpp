// Where the settings live: CONFIG.TXT on SD for people, a CRC-checked copy in EEPROM for a
// machine without a card (firmware/mega/CONFIG.md).
#include "config_store.h"

#include "crc32.h"

namespace mega {

namespace {
constexpr uint8_t kMagic0 = 'U', kMagic1 = 'V', kVersion = 1;
constexpr uint16_t kValuesEnd = 4 + 4 * kKeyCount;
constexpr const char* kTempFile = "CONFIG.NEW";
}  // namespace

uint8_t ConfigStore::imageByte(uint16_t i) const {
  if (i == 0) return kMagic0;
  if (i == 1) return kMagic1;
  if (i == 2) return kVersion;
  if (i == 3) return kKeyCount;
  if (i < kValuesEnd) {
    uint32_t v = static_cast<uint32_t>(c_.raw()[(i - 4) / 4]);
    return static_cast<uint8_t>(v >> (8 * ((i - 4) % 4)));
  }
  return static_cast<uint8_t>(crc_ >> (8 * (i - kValuesEnd)));
}

uint8_t ConfigStore::load() {
  c_.defaults();
  uint8_t from = kFromDefaults;
  if (loadEeprom()) from |= kFromEeprom;
  if (loadFile()) from |= kFromFile;
  return from;
}

bool ConfigStore::loadEeprom() {
  while (!ee_.ready()) {
    // At most the last byte of a save still being written: 3.4 ms, once, at M501 right after M500.
  }
  uint8_t head[4] = {ee_.read(0), ee_.read(1), ee_.read(2), ee_.read(3)};
  if (head[0] != kMagic0 || head[1] != kMagic1 || head[2] != kVersion || head[3] != kKeyCount) return false;
  uint32_t crc = 0;
  for (uint16_t i = 0; i < kValuesEnd; i++) {
    char b = static_cast<char>(ee_.read(i));
    crc = uv::crc32Update(crc, &b, 1);
  }
  uint32_t stored = 0;
  for (uint8_t i = 0; i < 4; i++) stored |= static_cast<uint32_t>(ee_.read(kValuesEnd + i)) << (8 * i);
  if (stored != crc) return false;
  for (uint8_t k = 0; k < kKeyCount; k++) {
    uint32_t v = 0;
    for (uint8_t i = 0; i < 4; i++) v |= static_cast<uint32_t>(ee_.read(4 + 4 * k + i)) << (8 * i);
    c_.setHeld(static_cast<Key>(k), static_cast<int32_t>(v));  // a value out of range keeps its default
  }
  return true;
}

bool ConfigStore::loadFile() {
  if (!sd_.present()) return false;
  FileHandle f = sd_.open(kConfigFile, Storage::Mode::Read);
  if (f < 0) return false;
  LineReader lines(sd_, f);
  char line[64];
  uint8_t len;
  bool tooLong;
  while (lines.next(line, sizeof line - 1, len, tooLong)) {
    if (!tooLong) applyConfigLine(c_, line, len);
  }
  sd_.close(f);
  return true;
}

bool ConfigStore::writeFile() {
  FileHandle f = sd_.open(kTempFile, Storage::Mode::Create);
  if (f < 0) return false;
  bool ok = true;
  char line[kKeyNameMax + 3 + kValueTextMax + 2];
  for (uint8_t k = 0; k < kKeyCount && ok; k++) {
    uint8_t n = formatConfigLine(c_, static_cast<Key>(k), line);
    line[n++] = '\n';
    ok = sd_.write(f, line, n);
  }
  ok = sd_.sync(f) && ok;
  sd_.close(f);
  // The new file is complete before the old one goes; if power fails in between, the EEPROM
  // copy (being written too) holds the same values.
  if (ok) ok = (!sd_.exists(kConfigFile) || sd_.remove(kConfigFile)) && sd_.rename(kTempFile, kConfigFile);
  return ok;
}

uint8_t ConfigStore::save() {
  crc_ = 0;
  for (uint16_t i = 0; i < kValuesEnd; i++) {
    char b = static_cast<char>(imageByte(i));
    crc_ = uv::crc32Update(crc_, &b, 1);
  }
  next_ = 0;
  if (!sd_.present()) return 0;
  return writeFile() ? 0 : 22;
}

void ConfigStore::poll() {
  while (saving() && ee_.ready()) {
    uint8_t b = imageByte(next_);
    uint16_t at = next_++;
    if (ee_.read(at) != b) {
      ee_.write(at, b);
      return;  // one write started: the EEPROM is busy for the next 3.4 ms
    }
  }
}

}  // namespace mega
