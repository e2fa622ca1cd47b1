// What the SSD1306 shows, composed from a snapshot and redrawn a changed row at a time.
#include "screen.h"

#include <string.h>

#include "nano_codec.h"
#include "progmem.h"

namespace mega {

namespace {
// One row composed every 3 ms at most: composing costs up to a few hundred µs (32-bit divisions),
// so most passes pay nothing, and a change still shows within a 24 ms sweep of the eight rows.
constexpr uint32_t kComposeEveryMs = 3;

// Decimal digits of v; no NUL. Below 65536 it divides by 10 with a multiply: the AVR has no divide
// instruction, and its 16-bit division routine (12 us) would cost over 100 us a row.
uint8_t decimal(uint32_t v, char* out) {
  char t[10];
  uint8_t n = 0;
  while (v > 0xffff) {
    uint32_t q = v / 10;
    t[n++] = static_cast<char>('0' + (v - q * 10));
    v = q;
  }
  uint16_t w = static_cast<uint16_t>(v);
  do {
    uint16_t q = static_cast<uint16_t>(static_cast<uint32_t>(w) * 52429u >> 19);  // w / 10, exact below 81920
    t[n++] = static_cast<char>('0' + (w - q * 10));
    w = q;
  } while (w);
  for (uint8_t i = 0; i < n; i++) out[i] = t[n - 1 - i];
  return n;
}

struct Line {
  char* out;
  uint8_t n;
  void put(const char* flash) {
    for (uint8_t i = 0; n < kScreenCols && uvFlashByte(flash + i); i++) out[n++] = static_cast<char>(uvFlashByte(flash + i));
  }
  void ram(const char* s) {
    for (; n < kScreenCols && *s; s++) out[n++] = *s;
  }
  void num(uint32_t v) {
    char t[11];
    t[decimal(v, t)] = 0;
    ram(t);
  }
  // A bed position in mm with `decimals` digits (1 or 2), right-aligned in `width`.
  void mm(int32_t um, uint8_t decimals, uint8_t width) {
    char t[12];
    uint8_t k = 0;
    uint32_t a = static_cast<uint32_t>(um < 0 ? -um : um);
    if (um < 0) t[k++] = '-';
    uint32_t whole = a / 1000;
    uint16_t f = static_cast<uint16_t>(a - whole * 1000);
    k = static_cast<uint8_t>(k + decimal(whole, t + k));
    t[k++] = '.';
    t[k++] = static_cast<char>('0' + f / 100);
    if (decimals > 1) t[k++] = static_cast<char>('0' + f / 10 % 10);
    if (decimals > 2) t[k++] = static_cast<char>('0' + f % 10);
    t[k] = 0;
    while (k < width && n < kScreenCols) {
      out[n++] = ' ';
      width--;
    }
    ram(t);
  }
  void deci(int16_t v) {
    char t[8];
    t[uv::formatDeciC(v, t)] = 0;
    ram(t);
  }
};

uint8_t checksum(const char* s) {
  uint8_t c = 0x5a;
  for (uint8_t i = 0; i < kScreenCols; i++) c = static_cast<uint8_t>((c << 1 | c >> 7) ^ static_cast<uint8_t>(s[i]));
  return c ? c : 1;  // 0 means "never drawn"
}
}  // namespace

void composeRow(const ScreenState& s, uint8_t r, char out[kScreenCols + 1]) {
  Line l{out, 0};
  switch (r) {
    case 0: {
      l.put(UV_P("UV "));
      static const char kIdle[] UV_FLASH = "ready", kHoming[] UV_FLASH = "homing", kBusy[] UV_FLASH = "busy",
                        kRunning[] UV_FLASH = "EXPOSING", kPaused[] UV_FLASH = "paused", kDone[] UV_FLASH = "job done",
                        kAborted[] UV_FLASH = "aborted", kHalted[] UV_FLASH = "HALTED M999";
      static const char* const kModes[] UV_FLASH = {kIdle, kHoming, kBusy, kRunning, kPaused, kDone, kAborted, kHalted};
      l.put(uvFlashPtr(kModes[static_cast<uint8_t>(s.mode)]));
      break;
    }
    case 1:
      if (!s.homed) {
        l.put(UV_P("not homed: G28"));
        break;
      }
      l.put(UV_P("X"));
      l.mm(s.um[0], 2, 7);
      l.put(UV_P("Y"));
      l.mm(s.um[1], 2, 7);
      break;
    case 2:
      l.put(UV_P("Z"));
      l.mm(s.um[2], 3, 7);
      break;
    case 3:
      if (!s.stops) break;
      l.put(UV_P("stop "));
      l.num(s.stop);
      l.put(UV_P("/"));
      l.num(s.stops);
      break;
    case 4:
      if (!s.stops || s.mode != ScreenState::Mode::Running) break;
      l.put(UV_P("left "));
      l.num(s.remainingS / 60);
      l.put(UV_P("m"));
      l.num(s.remainingS % 60);
      l.put(UV_P("s"));
      break;
    case 5:
      if (!s.nanoOnline) {
        l.put(UV_P("printhead silent"));
        break;
      }
      l.put(UV_P("T"));
      l.num(s.hottest);
      l.put(UV_P(" "));
      l.deci(s.hottestDeciC);
      l.put(UV_P("/"));
      l.deci(s.hottestLimitDeciC);
      l.put(UV_P("C"));
      break;
    case 6:
      if (!s.fault) break;
      l.put(UV_P("fault E"));
      l.num(s.fault);
      break;
    case 7:
      if (s.message) l.ram(s.message);
      break;
  }
  while (l.n < kScreenCols) out[l.n++] = ' ';
  out[kScreenCols] = 0;
}

void Screen::invalidate() { memset(shown_, 0, sizeof shown_); }

bool Screen::due(uint32_t nowMs) {
  display_.poll(nowMs);
  if (display_.takeLost()) invalidate();
  return display_.ready() && (!any_ || nowMs - lastMs_ >= kComposeEveryMs);
}

bool Screen::draw(const ScreenState& s, uint32_t nowMs) {
  any_ = true;
  lastMs_ = nowMs;
  uint8_t r = next_;
  next_ = static_cast<uint8_t>((r + 1) % kScreenRows);
  char text[kScreenCols + 1];
  composeRow(s, r, text);
  uint8_t c = checksum(text);
  if (c == shown_[r]) return false;
  display_.row(r, text);
  shown_[r] = c;
  return true;
}

}  // namespace mega
