// Small bounded scanners for decimal numbers in protocol text, shared by the codecs.
#include "text_scan.h"

namespace uv {

const char* scanUnsigned(const char* p, const char* end, uint8_t maxDigits, uint32_t limit, uint32_t& out) {
  uint32_t v = 0;
  uint8_t n = 0;
  while (p < end && *p >= '0' && *p <= '9') {
    if (++n > maxDigits) return nullptr;
    uint32_t d = static_cast<uint32_t>(*p - '0');
    if (v > (limit - d) / 10) return nullptr;  // v*10 + d > limit
    v = v * 10 + d;
    p++;
  }
  if (n == 0) return nullptr;
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

size_t putUnsigned(uint32_t v, char* out) {
  char tmp[10];
  size_t n = 0;
  do {
    tmp[n++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v);
  for (size_t i = 0; i < n; i++) out[i] = tmp[n - 1 - i];
  return n;
}

size_t putSigned(int32_t v, char* out) {
  if (v >= 0) return putUnsigned(static_cast<uint32_t>(v), out);
  out[0] = '-';
  return 1 + putUnsigned(static_cast<uint32_t>(-(v + 1)) + 1u, out + 1);
}

bool startsWith(const char* p, const char* end, const char* literal) {
  while (*literal) {
    if (p >= end || *p != *literal) return false;
    p++;
    literal++;
  }
  return true;
}

}  // namespace uv
