// The Mega's settings (firmware/mega/CONFIG.md): the key table, values, ranges, and their text form.
#pragma once
#include <stddef.h>
#include <stdint.h>

#include "config_keys.h"  // Key, kKeyCount, kKeyNameMax: generated from firmware/mega/settings.toml

namespace mega {

// Longest text form of one value: "-2000000.000" or "-4096,-4096".
constexpr uint8_t kValueTextMax = 12;

inline Key operator+(Key k, uint8_t i) { return static_cast<Key>(static_cast<uint8_t>(k) + i); }

// Every value is held in thousandths (80 steps/mm = 80000). An LED offset pair is held as
// (dx << 16) | (dy & 0xffff), both whole cells.
class Config {
 public:
  Config() { defaults(); }
  void defaults();

  int32_t milli(Key k) const { return v_[static_cast<uint8_t>(k)]; }
  // The value in whole units, rounded towards zero (for keys that only take whole numbers).
  int32_t whole(Key k) const { return milli(k) / 1000; }
  int16_t pairX(Key k) const { return static_cast<int16_t>(static_cast<uint32_t>(milli(k)) >> 16); }
  int16_t pairY(Key k) const { return static_cast<int16_t>(milli(k) & 0xffff); }

  // Sets a key from its text form. Returns false (nothing changes) for a malformed or out-of-range value.
  bool set(Key k, const char* text, uint8_t len);
  // Sets a key from its held form (as raw() holds it). Returns false for a value outside the key's range.
  bool setHeld(Key k, int32_t held);
  // Writes the value's text form and a NUL into out (kValueTextMax + 1 bytes); returns its length.
  uint8_t format(Key k, char* out) const;

  const int32_t* raw() const { return v_; }
  int32_t* raw() { return v_; }

 private:
  int32_t v_[kKeyCount];
};

// Looks a key name up in [name, name+len). Returns false if it is not a key.
bool findKey(const char* name, uint8_t len, Key& out);
// Copies a key's name and a NUL into out (kKeyNameMax + 1 bytes); returns its length.
uint8_t keyName(Key k, char* out);

// Applies one `key = value` line of CONFIG.TXT. Returns true if it was taken; every other line
// (comments, blanks, unknown keys, malformed or out-of-range values) is skipped.
bool applyConfigLine(Config& c, const char* line, uint8_t len);
// Writes `key = value` (no newline, NUL-terminated) for one key; returns the length.
uint8_t formatConfigLine(const Config& c, Key k, char* out);
// Applies an M850 argument, `<key> <value>` or `<key>`. Returns 0 on success, with `query` set
// when only a key was given, or 50 (config_invalid).
uint8_t applyM850(Config& c, const char* text, uint8_t len, Key& key, bool& query);

}  // namespace mega
