// Parses a dialect line body into a command word and fixed-point parameters (protocol/mega.md §1).
#pragma once
#include <stdint.h>

namespace uv {

constexpr int32_t kMaxMilli = 2000000000;

struct Command {
  char letter;        // 'G' or 'M'
  uint16_t code;      // 0-9999
  uint32_t present;   // bit i: parameter 'A'+i is present
  uint32_t valued;    // bit i: it has a value (else it is a bare flag like `X`)
  int32_t milli[26];  // values in thousandths
  const char* text;   // rest of line for M23/M28/M30/M32/M850, else nullptr
  uint8_t textLen;

  bool has(char p) const { return present & (1ul << (p - 'A')); }
  bool hasValue(char p) const { return valued & (1ul << (p - 'A')); }
  int32_t value(char p) const { return milli[p - 'A']; }
  bool is(char l, uint16_t c) const { return letter == l && code == c; }
};

// A name on the card as the dialect takes it (after a leading `/`): 1-31 of A-Z a-z 0-9 _ . - ~.
// A name read back from the card (the checkpoint) is held to the same rule.
bool validFileName(const char* p, uint8_t n);

// `-?digits[.digits]` in [p, p+len) to thousandths, rounded half away from zero.
bool parseMilli(const char* p, uint8_t len, int32_t& out);

// Returns 0, or kUnknownCommand (10) / kBadParameter (11).
uint8_t parseCommand(const char* body, uint8_t len, Command& out);

}  // namespace uv
