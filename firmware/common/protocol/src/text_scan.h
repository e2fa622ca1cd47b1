// Small bounded scanners for decimal numbers in protocol text, shared by the codecs.
#pragma once
#include <stddef.h>
#include <stdint.h>

namespace uv {

// Parses an unsigned decimal of 1..maxDigits digits from [p, end) into out; returns
// the position after it or nullptr. Leading zeros are allowed. Values over limit fail.
const char* scanUnsigned(const char* p, const char* end, uint8_t maxDigits, uint32_t limit, uint32_t& out);

// Parses `-?d{1,maxInt}.d` (tenths) from [p, end); returns the position after it or nullptr.
const char* scanDeci(const char* p, const char* end, uint8_t maxInt, int16_t& out);

// Writes an unsigned decimal without leading zeros; returns the length (no NUL).
size_t putUnsigned(uint32_t v, char* out);
size_t putSigned(int32_t v, char* out);
// Copies a string kept in flash (UV_P) without its NUL; returns the length, as putUnsigned does.
size_t putFlash(const char* flash, char* out);

// Writes the low `digits` hex digits of v, lower case, most significant first (no NUL).
void putHex(uint32_t v, uint8_t digits, char* out);

// True if [p, p+n) equals the NUL-terminated literal.
bool startsWith(const char* p, const char* end, const char* literal);

}  // namespace uv
