// Parses a dialect line body into a command word and fixed-point parameters (protocol/mega.md §1).
#include "dialect_command.h"

#include <string.h>

#include "error_codes.h"

namespace uv {

namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
char upper(char c) { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 32) : c; }

bool fileNameChar(char c) {
  // `~` is in DOS short names, which OctoPrint makes for the card.
  return isDigit(c) || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' || c == '.' || c == '-' || c == '~';
}

enum class ArgKind : uint8_t { Params, FileName, Text };

ArgKind argKind(char letter, uint16_t code) {
  if (letter != 'M') return ArgKind::Params;
  if (code == 23 || code == 28 || code == 30 || code == 32) return ArgKind::FileName;
  if (code == 850 || code == 117) return ArgKind::Text;
  return ArgKind::Params;
}

}  // namespace

bool validFileName(const char* p, uint8_t n) {
  if (n == 0 || n > 31) return false;
  for (uint8_t i = 0; i < n; i++)
    if (!fileNameChar(p[i])) return false;
  return true;
}

bool parseMilli(const char* p, uint8_t len, int32_t& out) {
  const char* end = p + len;
  bool neg = p < end && *p == '-';
  if (neg) p++;
  uint32_t whole = 0;
  const char* start = p;
  while (p < end && isDigit(*p)) {
    whole = whole * 10 + static_cast<uint32_t>(*p - '0');
    // Checked at every digit, so `whole * 1000` below can never wrap: a number out of range is
    // refused, not read as another number.
    if (whole > static_cast<uint32_t>(kMaxMilli / 1000)) return false;
    p++;
  }
  if (p == start) return false;
  uint32_t frac = 0;
  bool roundUp = false;
  if (p < end) {
    if (*p != '.') return false;
    p++;
    const char* fracStart = p;
    uint8_t i = 0;
    while (p < end && isDigit(*p)) {
      if (i < 3) frac = frac * 10 + static_cast<uint32_t>(*p - '0');
      else if (i == 3) roundUp = *p >= '5';
      i++;
      p++;
    }
    if (p == fracStart || p != end) return false;
    for (; i < 3; i++) frac *= 10;
  }
  uint32_t v = whole * 1000 + frac + (roundUp ? 1 : 0);
  if (v > static_cast<uint32_t>(kMaxMilli)) return false;
  out = neg ? -static_cast<int32_t>(v) : static_cast<int32_t>(v);
  return true;
}

uint8_t parseCommand(const char* body, uint8_t len, Command& out) {
  memset(&out, 0, sizeof(out));
  const char* p = body;
  const char* end = body + len;
  if (p >= end) return kUnknownCommand;
  out.letter = upper(*p++);
  if (out.letter != 'G' && out.letter != 'M') return kUnknownCommand;
  uint8_t digits = 0;
  while (p < end && isDigit(*p)) {
    if (++digits > 4) return kUnknownCommand;
    out.code = static_cast<uint16_t>(out.code * 10 + (*p++ - '0'));
  }
  if (digits == 0 || (p < end && *p != ' ')) return kUnknownCommand;

  ArgKind kind = argKind(out.letter, out.code);
  if (kind != ArgKind::Params) {
    while (p < end && *p == ' ') p++;
    uint8_t n = static_cast<uint8_t>(end - p);
    if (kind == ArgKind::Text)
      while (n > 0 && p[n - 1] == ' ') n--;
    // M117 alone clears the panel's message, as Marlin's does; every other text or name is required.
    if (n == 0 && !(out.letter == 'M' && out.code == 117)) return kBadParameter;
    if (kind == ArgKind::FileName) {
      // A leading `/` names the card's root, its only folder (OctoPrint writes it).
      if (n > 0 && *p == '/') {
        p++;
        n--;
      }
      if (!validFileName(p, n)) return kBadParameter;
    }
    out.text = p;
    out.textLen = n;
    return 0;
  }

  while (p < end) {
    while (p < end && *p == ' ') p++;
    if (p >= end) break;
    const char* tokEnd = p;
    while (tokEnd < end && *tokEnd != ' ') tokEnd++;
    char letter = upper(*p);
    if (letter < 'A' || letter > 'Z') return kBadParameter;
    uint32_t bit = 1ul << (letter - 'A');
    if (out.present & bit) return kBadParameter;
    out.present |= bit;
    if (tokEnd - p > 1) {
      if (!parseMilli(p + 1, static_cast<uint8_t>(tokEnd - p - 1), out.milli[letter - 'A'])) return kBadParameter;
      out.valued |= bit;
    }
    p = tokEnd;
  }
  return 0;
}

}  // namespace uv
