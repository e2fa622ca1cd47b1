// The Mega's settings (firmware/mega/CONFIG.md): the key table, values, ranges, and their text form.
#include "config.h"

#include <string.h>

#include "dialect_command.h"
#include "progmem.h"
#include "text_scan.h"

namespace mega {

namespace {

enum Flags : uint8_t { kDecimal = 0, kWhole = 1, kPair = 2, kOff = 4 };  // kOff: 0 is taken too, below the range (off)

struct KeySpec {
  char name[kKeyNameMax + 1];
  int32_t def, min, max;  // thousandths; for a pair: the default packed, and each half's bounds
  uint8_t flags;
};

constexpr int32_t pair(int16_t dx, int16_t dy) {
  return static_cast<int32_t>((static_cast<uint32_t>(static_cast<uint16_t>(dx)) << 16) | static_cast<uint16_t>(dy));
}

// The ranges keep the machine safe whatever a file or a host says: a zero steps/mm or speed would
// divide by zero, and no soft thermal limit may sit above the Nano's 60 °C hard limit.
const KeySpec kSpecs[kKeyCount] UV_FLASH = {
#include "config_specs.inc"  // generated from firmware/mega/settings.toml (scripts/settings.py)
};

const KeySpec& spec(Key key) { return kSpecs[static_cast<uint8_t>(key)]; }
int32_t specDef(Key key) { return uvFlashDword(&spec(key).def); }
int32_t specMin(Key key) { return uvFlashDword(&spec(key).min); }
int32_t specMax(Key key) { return uvFlashDword(&spec(key).max); }
uint8_t specFlags(Key key) { return uvFlashByte(&spec(key).flags); }

bool isSpace(char c) { return c == ' ' || c == '\t'; }

// A whole number of cells in [min, max]: `-?digits`.
bool scanCell(const char* p, uint8_t len, int32_t min, int32_t max, int32_t& out) {
  int32_t milli;
  if (!uv::parseMilli(p, len, milli) || memchr(p, '.', len)) return false;
  out = milli / 1000;
  return out >= min && out <= max;
}

}  // namespace

void Config::defaults() {
  for (uint8_t i = 0; i < kKeyCount; i++) v_[i] = specDef(static_cast<Key>(i));
}

bool Config::set(Key key, const char* text, uint8_t len) {
  if (specFlags(key) & kPair) {
    int32_t lo = specMin(key), hi = specMax(key);
    const char* comma = static_cast<const char*>(memchr(text, ',', len));
    if (!comma) return false;
    int32_t dx, dy;
    uint8_t first = static_cast<uint8_t>(comma - text);
    if (!scanCell(text, first, lo, hi, dx) || !scanCell(comma + 1, static_cast<uint8_t>(len - first - 1), lo, hi, dy)) return false;
    v_[static_cast<uint8_t>(key)] = pair(static_cast<int16_t>(dx), static_cast<int16_t>(dy));
    return true;
  }
  int32_t milli;
  return uv::parseMilli(text, len, milli) && setHeld(key, milli);
}

bool Config::setHeld(Key key, int32_t held) {
  int32_t lo = specMin(key), hi = specMax(key);
  if (specFlags(key) & kPair) {
    int16_t dx = static_cast<int16_t>(static_cast<uint32_t>(held) >> 16), dy = static_cast<int16_t>(held & 0xffff);
    if (dx < lo || dx > hi || dy < lo || dy > hi) return false;
  } else if ((held < lo && !(held == 0 && (specFlags(key) & kOff))) || held > hi || ((specFlags(key) & kWhole) && held % 1000)) {
    return false;
  }
  v_[static_cast<uint8_t>(key)] = held;
  return true;
}

uint8_t Config::format(Key key, char* out) const {
  size_t n;
  if (specFlags(key) & kPair) {
    n = uv::putSigned(pairX(key), out);
    out[n++] = ',';
    n += uv::putSigned(pairY(key), out + n);
  } else {
    int32_t v = milli(key);
    n = 0;
    if (v < 0) {
      out[n++] = '-';
      v = -v;
    }
    n += uv::putUnsigned(static_cast<uint32_t>(v / 1000), out + n);
    uint32_t frac = static_cast<uint32_t>(v % 1000);
    if (frac) {
      out[n++] = '.';
      for (uint32_t div = 100; frac; div /= 10) {
        out[n++] = static_cast<char>('0' + frac / div);
        frac %= div;
      }
    }
  }
  out[n] = 0;
  return static_cast<uint8_t>(n);
}

bool findKey(const char* name, uint8_t len, Key& out) {
  if (len == 0 || len > kKeyNameMax) return false;
  for (uint8_t i = 0; i < kKeyCount; i++) {
    const char* s = kSpecs[i].name;
    uint8_t j = 0;
    while (j < len && uvFlashByte(s + j) == static_cast<uint8_t>(name[j])) j++;
    if (j == len && uvFlashByte(s + j) == 0) {
      out = static_cast<Key>(i);
      return true;
    }
  }
  return false;
}

uint8_t keyName(Key key, char* out) {
  const char* s = spec(key).name;
  uint8_t n = 0;
  while ((out[n] = static_cast<char>(uvFlashByte(s + n))) != 0) n++;
  return n;
}

bool applyConfigLine(Config& c, const char* line, uint8_t len) {
  const char* p = line;
  const char* end = line + len;
  while (p < end && isSpace(*p)) p++;
  const char* name = p;
  while (p < end && !isSpace(*p) && *p != '=') p++;
  Key key;
  if (!findKey(name, static_cast<uint8_t>(p - name), key)) return false;
  while (p < end && isSpace(*p)) p++;
  if (p == end || *p != '=') return false;
  p++;
  while (p < end && isSpace(*p)) p++;
  while (end > p && isSpace(end[-1])) end--;
  return c.set(key, p, static_cast<uint8_t>(end - p));
}

uint8_t formatConfigLine(const Config& c, Key key, char* out) {
  uint8_t n = keyName(key, out);
  out[n++] = ' ';  // not a " = " literal: on the AVR that would take RAM
  out[n++] = '=';
  out[n++] = ' ';
  return static_cast<uint8_t>(n + c.format(key, out + n));
}

uint8_t applyM850(Config& c, const char* text, uint8_t len, Key& key, bool& query) {
  const char* end = text + len;
  const char* space = text;
  while (space < end && *space != ' ') space++;
  if (!findKey(text, static_cast<uint8_t>(space - text), key)) return 50;
  const char* value = space;
  while (value < end && *value == ' ') value++;
  query = value == end;
  if (query) return 0;
  return c.set(key, value, static_cast<uint8_t>(end - value)) ? 0 : 50;
}

}  // namespace mega
