// Small bounded scanners for decimal numbers in protocol text, shared by the codecs.
#include "text_scan.h"

#include "progmem.h"

namespace uv {

// No division anywhere here: on an AVR one 32-bit division costs about 700 cycles, and these run
// on every digit the printhead and the Mega read or write.
const char* scanUnsigned(const char* p, const char* end, uint8_t maxDigits, uint32_t limit, uint32_t& out) {
  uint32_t v = 0;
  uint8_t n = 0;
  while (p < end && *p >= '0' && *p <= '9') {
    if (++n > maxDigits) return nullptr;
    uint8_t d = static_cast<uint8_t>(*p - '0');
    if (v > 429496729u || (v == 429496729u && d > 5)) return nullptr;  // would pass 2^32 - 1
    v = v * 10 + d;
    p++;
  }
  if (n == 0 || v > limit) return nullptr;
  out = v;
  return p;
}

const char* scanDeci(const char* p, const char* end, uint8_t maxInt, int16_t& out) {
  bool neg = p < end && *p == '-';
  if (neg) p++;
  uint32_t whole = 0;
  p = scanUnsigned(p, end, maxInt, 9999, whole);
  if (!p || p + 2 > end || p[0] != '.' || p[1] < '0' || p[1] > '9') return nullptr;
  int32_t v = static_cast<int32_t>(whole) * 10 + (p[1] - '0');
  out = static_cast<int16_t>(neg ? -v : v);
  return p + 2;
}

namespace {

// Both AVRs keep these tables in flash, where their RAM is short (the Nano's dose records took the
// 44 bytes; its reply times, measured in nano_sim_test, stay far inside their budget).
#ifdef __AVR__
#define UV_TABLE UV_FLASH
inline uint16_t tablePower(const uint16_t* p) { return pgm_read_word(p); }
inline uint32_t tablePower(const uint32_t* p) { return pgm_read_dword(p); }
#else
#define UV_TABLE
inline uint16_t tablePower(const uint16_t* p) { return *p; }
inline uint32_t tablePower(const uint32_t* p) { return *p; }
#endif

// Digits by repeated subtraction of powers of ten, from the largest that can matter.
template <class T, size_t N>
size_t putDigits(T v, const T (&powers)[N], char* out) {
  size_t n = 0;
  for (size_t i = 0; i < N; i++) {
    T power = tablePower(&powers[i]);
    char digit = '0';
    while (v >= power) {
      v = static_cast<T>(v - power);
      digit++;
    }
    if (digit != '0' || n) out[n++] = digit;
  }
  out[n++] = static_cast<char>('0' + v);
  return n;
}

}  // namespace

size_t putUnsigned(uint32_t v, char* out) {
  // Most numbers on the links (masks, temperatures, line numbers) fit 16 bits, where an AVR
  // compares and subtracts in a quarter of the time.
  static const uint16_t kSmall[] UV_TABLE = {10000u, 1000u, 100u, 10u};
  static const uint32_t kLarge[] UV_TABLE = {1000000000u, 100000000u, 10000000u, 1000000u, 100000u, 10000u, 1000u, 100u, 10u};
  if (v <= 0xFFFFu) return putDigits(static_cast<uint16_t>(v), kSmall, out);
  return putDigits(v, kLarge, out);
}

size_t putSigned(int32_t v, char* out) {
  if (v >= 0) return putUnsigned(static_cast<uint32_t>(v), out);
  out[0] = '-';
  return 1 + putUnsigned(static_cast<uint32_t>(-(v + 1)) + 1u, out + 1);
}

void putHex(uint32_t v, uint8_t digits, char* out) {
  for (uint8_t i = digits; i > 0; i--) {
    uint8_t d = v & 0xF;
    out[i - 1] = static_cast<char>(d < 10 ? '0' + d : 'a' + d - 10);
    v >>= 4;
  }
}

bool startsWith(const char* p, const char* end, const char* literal) {
  while (*literal) {
    if (p >= end || *p != *literal) return false;
    p++;
    literal++;
  }
  return true;
}

size_t putFlash(const char* flash, char* out) {
  size_t n = uvStrlenP(flash);
  uvMemcpyP(out, flash, n);
  return n;
}

}  // namespace uv
