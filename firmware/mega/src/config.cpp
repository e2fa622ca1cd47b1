// The Mega's settings (firmware/mega/CONFIG.md): the key table, values, ranges, and their text form.
#include "config.h"

#include <string.h>

#include "dialect_command.h"
#include "progmem.h"
#include "text_scan.h"

namespace mega {

namespace {

enum Flags : uint8_t { kDecimal = 0, kWhole = 1, kPair = 2 };

struct KeySpec {
  char name[kKeyNameMax + 1];
  int32_t def, min, max;  // thousandths; for a pair: the default packed, and each half's bounds
  uint8_t flags;
};

constexpr int32_t k = 1000;
constexpr int32_t pair(int16_t dx, int16_t dy) {
  return static_cast<int32_t>((static_cast<uint32_t>(static_cast<uint16_t>(dx)) << 16) | static_cast<uint16_t>(dy));
}

// The ranges keep the machine safe whatever a file or a host says: a zero steps/mm or speed would
// divide by zero, and no soft thermal limit may sit above the Nano's 60 °C hard limit.
const KeySpec kSpecs[kKeyCount] UV_FLASH = {
    {"steps_per_mm.x", 80 * k, 1 * k, 2000 * k, kDecimal},
    {"steps_per_mm.y", 80 * k, 1 * k, 2000 * k, kDecimal},
    {"steps_per_mm.z", 400 * k, 1 * k, 10000 * k, kDecimal},
    {"bed.x", 200 * k, 1 * k, 2000 * k, kDecimal},
    {"bed.y", 200 * k, 1 * k, 2000 * k, kDecimal},
    {"bed.z", 40 * k, 1 * k, 500 * k, kDecimal},
    {"speed.travel", 100 * k, 1 * k, 500 * k, kDecimal},
    {"speed.z", 10 * k, k / 10, 100 * k, kDecimal},
    {"speed.jog_slow", 5 * k, k / 10, 100 * k, kDecimal},
    {"speed.jog_fast", 50 * k, 1 * k, 500 * k, kDecimal},
    {"speed.home", 40 * k, 1 * k, 200 * k, kDecimal},
    {"accel.x", 2000 * k, 10 * k, 20000 * k, kDecimal},
    {"accel.y", 1500 * k, 10 * k, 20000 * k, kDecimal},
    {"accel.z", 200 * k, 1 * k, 5000 * k, kDecimal},
    {"settle_ms", 2 * k, 0, 1000 * k, kWhole},
    {"stop_overhead_us", 4300 * k, 0, 100000 * k, kWhole},
    {"invert.x", 0, 0, 1 * k, kWhole},
    {"invert.y", 0, 0, 1 * k, kWhole},
    {"invert.z", 0, 0, 1 * k, kWhole},
    {"pitch.x", 50 * k, 1 * k, 100000 * k, kWhole},
    {"pitch.y", 50 * k, 1 * k, 100000 * k, kWhole},
    {"led.offset.0", pair(0, 0), -4096, 4096, kPair},
    {"led.offset.1", pair(0, 1), -4096, 4096, kPair},
    {"led.offset.2", pair(0, 2), -4096, 4096, kPair},
    {"led.offset.3", pair(0, 3), -4096, 4096, kPair},
    {"led.irradiance.0", 30000 * k, 1 * k, 2000000 * k, kWhole},
    {"led.irradiance.1", 30000 * k, 1 * k, 2000000 * k, kWhole},
    {"led.irradiance.2", 30000 * k, 1 * k, 2000000 * k, kWhole},
    {"led.irradiance.3", 30000 * k, 1 * k, 2000000 * k, kWhole},
    {"led.gain.0", 1000 * k, 1 * k, 10000 * k, kWhole},
    {"led.gain.1", 1000 * k, 1 * k, 10000 * k, kWhole},
    {"led.gain.2", 1000 * k, 1 * k, 10000 * k, kWhole},
    {"led.gain.3", 1000 * k, 1 * k, 10000 * k, kWhole},
    {"thermal.limit.0", 55 * k, 0, 60 * k, kDecimal},
    {"thermal.limit.1", 55 * k, 0, 60 * k, kDecimal},
    {"thermal.limit.2", 55 * k, 0, 60 * k, kDecimal},
    {"thermal.limit.3", 55 * k, 0, 60 * k, kDecimal},
    {"thermal.limit.4", 50 * k, 0, 60 * k, kDecimal},
    {"thermal.limit.5", 50 * k, 0, 60 * k, kDecimal},
    {"thermal.coeff", 0, -1000 * k, 1000 * k, kWhole},
    {"esp.port", 2 * k, 2 * k, 3 * k, kWhole},
    {"light.pin", 57 * k, 0, 69 * k, kWhole},
    {"mesh.nx", 3 * k, 3 * k, 9 * k, kWhole},
    {"mesh.ny", 3 * k, 3 * k, 9 * k, kWhole},
    {"mesh.margin", 10 * k, 0, 100 * k, kDecimal},
    {"report.position_ms", 0, 0, 60000 * k, kWhole},
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
  } else if (held < lo || held > hi || ((specFlags(key) & kWhole) && held % 1000)) {
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
