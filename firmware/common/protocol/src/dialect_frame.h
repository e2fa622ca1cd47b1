// Line framing of the Mega dialect: `N<n> <body>*<cs>` or a plain body (protocol/mega.md §1).
#pragma once
#include <stddef.h>
#include <stdint.h>

namespace uv {

constexpr uint8_t kDialectMaxLine = 96;
// The last line number: one short of int32's end, so that `Resend: <last + 1>` always names a number
// (protocol/mega.md §1). A larger N makes the line corrupt (E2).
constexpr uint32_t kMaxLineNumber = 2147483646u;

struct Frame {
  uint8_t error;      // 0 = good frame, else an ErrorCode 1-6
  bool numbered;      // the line starts with 'N'
  bool hasN;          // n is known (a good numbered frame, or an intact prefix)
  int32_t n;          // -1 only for printrun's `N-1 M110 N-1`
  const char* body;   // points into the line: comment stripped, trimmed
  uint8_t bodyLen;
};

uint8_t xorChecksum(const char* text, size_t len);

// Parses a split line (without terminator).
Frame parseFrame(const char* text, uint8_t len, bool overflow);

// Writes `N<n> <body>*<cs>#<crc16>` (no newline) and a NUL; returns the length or 0 if it won't fit.
size_t encodeFrame(uint32_t n, const char* body, char* out, size_t size);

}  // namespace uv
