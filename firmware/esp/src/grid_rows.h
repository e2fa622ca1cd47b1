// Reads a POST /print body's gridData one row at a time from the spooled file, so that only one
// row of cells is ever in RAM (protocol/esp.md "Limits").
//
// Why not ArduinoJson for the rows too: it keeps every element of a parsed array in an 8-byte
// slot on the ESP8266, so one 4096-cell row would take 32 KB of a heap of about 40 KB. The header
// is parsed by the JSON library with gridData filtered out, which also checks the whole body's
// syntax; this walker then only has to find gridData, frame its rows and read 0-255 integers.
// It applies the same checks in the same order as the schema validator (print-request.ts): the
// row count, then each row's length, then its cells, so both give the same error for a body.
//
// Reader: int read() returning the next byte or -1 at the end.
#pragma once
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "print_request.h"

namespace uv {
namespace esp {

template <class Reader>
class GridRows {
 public:
  explicit GridRows(Reader& reader) : r_(reader) {}

  // Finds the root object's "gridData" member and steps inside its '['.
  GridDataShape open() {
    advance();
    space();
    if (c_ != '{') return {};
    advance();
    for (;;) {
      space();
      if (c_ != '"') return {};
      bool isGrid = keyIs("gridData");
      space();
      if (c_ != ':') return {};
      advance();
      space();
      if (isGrid) {
        if (c_ != '[') return {true, false};
        advance();
        return {true, true};
      }
      skipValue();
      space();
      if (c_ != ',') return {};
      advance();
    }
  }

  // Row `index` into cells[h.cols]. False when the job is at fault (e says where); a later
  // row-count error still takes precedence over a row's own error, as in the schema validator.
  bool next(uint16_t index, const JobHeader& h, uint8_t* cells, RequestError& e) {
    space();
    if (index > 0) {
      if (c_ == ']') return countError(e);
      advance();  // ','
      space();
    } else if (c_ == ']') {
      return countError(e);
    }
    RequestError rowError{};
    if (!row(index, h, cells, rowError)) {
      uint32_t seen = index + 1u + skipRest();
      if (seen != h.rows) return countError(e);
      e = rowError;
      return false;
    }
    return true;
  }

  // After the last row: gridData must end here.
  bool finish(RequestError& e) {
    space();
    if (c_ == ']') return true;
    return countError(e);
  }

 private:
  static bool isSpace(int c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  void advance() { c_ = r_.read(); }
  void space() {
    while (isSpace(c_)) advance();
  }

  // At a '"': reads the string, true when it is exactly `want` (escapes are compared as written).
  bool keyIs(const char* want) {
    size_t i = 0, n = strlen(want);
    bool same = true;
    advance();
    while (c_ >= 0 && c_ != '"') {
      if (c_ == '\\') {
        same = false;
        advance();
      }
      same = same && i < n && c_ == want[i];
      i++;
      advance();
    }
    advance();
    return same && i == n;
  }

  void skipString() {
    advance();
    while (c_ >= 0 && c_ != '"') {
      if (c_ == '\\') advance();
      advance();
    }
    advance();
  }

  // Any JSON value; the body's syntax was already checked by the header parse.
  void skipValue() {
    if (c_ == '"') return skipString();
    if (c_ == '[' || c_ == '{') {
      uint16_t depth = 0;
      do {
        if (c_ == '"') {
          skipString();
          continue;
        }
        if (c_ == '[' || c_ == '{') depth++;
        if (c_ == ']' || c_ == '}') depth--;
        advance();
      } while (depth && c_ >= 0);
      return;
    }
    while (c_ >= 0 && c_ != ',' && c_ != ']' && c_ != '}' && !isSpace(c_)) advance();
  }

  // Skips the rest of gridData, returning how many more rows it held.
  uint32_t skipRest() {
    uint32_t rows = 0;
    for (;;) {
      space();
      if (c_ != ',') break;
      advance();
      space();
      skipValue();
      rows++;
    }
    return rows;
  }

  bool countError(RequestError& e) { return detail::fail(e, "/gridData", "array of the wrong size"); }

  // One row; its length is judged before its cells. The reader is left after the row.
  bool row(uint16_t index, const JobHeader& h, uint8_t* cells, RequestError& e) {
    char p[48];
    detail::join(p, sizeof p, "/gridData", static_cast<unsigned long>(index));
    if (c_ != '[') {
      skipValue();
      return detail::fail(e, p, "array of the wrong size");
    }
    advance();
    space();
    uint32_t n = 0;
    int32_t badCell = -1;
    if (c_ != ']') {
      for (;;) {
        space();
        int v = n < h.cols ? cell() : (skipValue(), 0);
        if (v < 0 && badCell < 0) badCell = static_cast<int32_t>(n);
        if (n < h.cols && v >= 0) cells[n] = static_cast<uint8_t>(v);
        n++;
        space();
        if (c_ != ',') break;
        advance();
      }
    }
    advance();  // ']'
    if (n != h.cols) return detail::fail(e, p, "array of the wrong size");
    if (badCell >= 0) {
      char q[48];
      detail::join(q, sizeof q, p, static_cast<unsigned long>(badCell));
      return detail::fail(e, q, "must be an integer in range");
    }
    return true;
  }

  // A cell: a JSON number with an integral value 0-255 (255.0 and 2.55e2 count, as in the JSON
  // libraries), or -1 for anything else.
  int cell() {
    bool number = c_ == '-' || (c_ >= '0' && c_ <= '9');
    if (!number) {
      skipValue();
      return -1;
    }
    char token[33];
    uint8_t n = 0;
    bool tooLong = false;
    while ((c_ >= '0' && c_ <= '9') || c_ == '-' || c_ == '+' || c_ == '.' || c_ == 'e' || c_ == 'E') {
      if (n < sizeof token - 1) token[n++] = static_cast<char>(c_);
      else tooLong = true;
      advance();
    }
    token[n] = 0;
    if (tooLong) return -1;
    char* end = nullptr;
    double v = strtod(token, &end);
    if (end != token + n || !(v >= 0 && v <= 255) || v != static_cast<double>(static_cast<int>(v))) return -1;
    return static_cast<int>(v);
  }

  Reader& r_;
  int c_ = 0;
};

}  // namespace esp
}  // namespace uv
