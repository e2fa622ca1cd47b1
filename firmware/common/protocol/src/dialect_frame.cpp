// Line framing of the Mega dialect: `N<n> <body>*<cs>` or a plain body (protocol/mega.md §1).
#include "dialect_frame.h"

#include <string.h>

#include "crc16.h"
#include "line_splitter.h"
#include "text_scan.h"

namespace uv {

uint8_t xorChecksum(const char* text, size_t len) {
  uint8_t x = 0;
  for (size_t i = 0; i < len; i++) x ^= static_cast<uint8_t>(text[i]);
  return x;
}

namespace {

// Strips a ';' comment and surrounding spaces from [p, end).
void trimBody(const char* p, const char* end, Frame& f) {
  const char* semi = static_cast<const char*>(memchr(p, ';', static_cast<size_t>(end - p)));
  if (semi) end = semi;
  while (p < end && *p == ' ') p++;
  while (end > p && end[-1] == ' ') end--;
  f.body = p;
  f.bodyLen = static_cast<uint8_t>(end - p);
}

// `N<digits> ` (or `N-1 `) with the number in range: where the body may start, else nullptr.
const char* numberPrefix(const char* text, const char* end, int32_t& n) {
  if (end - text >= 4 && text[1] == '-' && text[2] == '1' && text[3] == ' ') {
    n = -1;
    return text + 3;
  }
  uint32_t u = 0;
  const char* p = scanUnsigned(text + 1, end, 10, kMaxLineNumber, u);
  n = static_cast<int32_t>(u);
  return (p && p < end && *p == ' ') ? p : nullptr;
}

Frame fail(Frame f, uint8_t error, const char* text, const char* end) {
  f.error = error;
  if (f.numbered) f.hasN = numberPrefix(text, end, f.n) != nullptr;
  return f;
}

}  // namespace

Frame parseFrame(const char* text, uint8_t len, bool overflow) {
  Frame f = {0, len > 0 && text[0] == 'N', false, 0, text, 0};
  const char* end = text + len;
  if (overflow) return fail(f, 5, text, end);
  if (!isPrintable(text, len)) return fail(f, 1, text, end);
  if (!f.numbered) {
    trimBody(text, end, f);
    if (memchr(f.body, '*', f.bodyLen)) return fail(f, 4, text, end);
    return f;
  }
  const char* star = nullptr;
  for (const char* p = end; p > text; p--)
    if (p[-1] == '*') {
      star = p - 1;
      break;
    }
  int32_t n = 0;
  const char* afterNumber = numberPrefix(text, star ? star : end, n);
  if (!star) return fail(f, afterNumber ? 3 : 2, text, end);
  uint32_t cs = 0;
  size_t headLen = static_cast<size_t>(star - text);
  const char* csEnd = scanUnsigned(star + 1, end, 3, 255, cs);
  if (!afterNumber || !csEnd || cs != xorChecksum(text, headLen)) return fail(f, 2, text, end);
  if (csEnd != end) {  // the optional CRC-16: `#` and 4 lower-case hex digits
    char want[5];
    crc16Hex(crc16(text, headLen), want);
    if (end - csEnd != 5 || *csEnd != '#' || memcmp(csEnd + 1, want, 4) != 0) return fail(f, 2, text, end);
  }
  while (afterNumber < star && *afterNumber == ' ') afterNumber++;
  f.hasN = true;
  f.n = n;
  trimBody(afterNumber, star, f);
  return f;
}

size_t encodeFrame(uint32_t n, const char* body, char* out, size_t size) {
  size_t bodyLen = strlen(body);
  char num[10];
  size_t numLen = putUnsigned(n, num);
  size_t headLen = 1 + numLen + 1 + bodyLen;
  if (headLen + 10 > size) return 0;
  size_t k = 0;
  out[k++] = 'N';
  memcpy(out + k, num, numLen);
  k += numLen;
  out[k++] = ' ';
  memcpy(out + k, body, bodyLen);
  k += bodyLen;
  uint8_t cs = xorChecksum(out, k);
  uint16_t crc = crc16(out, k);
  out[k++] = '*';
  k += putUnsigned(cs, out + k);
  out[k++] = '#';
  crc16Hex(crc, out + k);
  k += 4;
  out[k] = '\0';
  return k;
}

}  // namespace uv
