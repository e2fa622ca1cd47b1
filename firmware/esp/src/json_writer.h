// A JSON writer into a caller's buffer, for the ESP's live messages and status: no heap, commas
// placed by itself, strings escaped. The bridge core writes JSON on the host too, where
// ArduinoJson is not available; parsing stays with the JSON libraries (print_request.h's views).
// Its text is whole or nothing: once it runs out of room, text() is "" and ok() false, so a cut-off
// object never reaches a file, a socket or a client.
#pragma once
#include <stdint.h>
#include <stdio.h>
#include <string.h>

namespace uv {
namespace esp {

// The length of the well-formed UTF-8 sequence at s (RFC 3629: no overlong forms, no
// surrogates, nothing past U+10FFFF), or 0.
inline uint8_t utf8Sequence(const char* s, size_t left) {
  const unsigned char* u = reinterpret_cast<const unsigned char*>(s);
  uint8_t n;
  unsigned char lo = 0x80, hi = 0xBF;  // the range of the second byte
  if (u[0] >= 0xC2 && u[0] <= 0xDF) n = 2;
  else if (u[0] >= 0xE0 && u[0] <= 0xEF) n = 3, lo = u[0] == 0xE0 ? 0xA0 : 0x80, hi = u[0] == 0xED ? 0x9F : 0xBF;
  else if (u[0] >= 0xF0 && u[0] <= 0xF4) n = 4, lo = u[0] == 0xF0 ? 0x90 : 0x80, hi = u[0] == 0xF4 ? 0x8F : 0xBF;
  else return 0;
  if (left < n || u[1] < lo || u[1] > hi) return 0;
  for (uint8_t k = 2; k < n; k++)
    if (u[k] < 0x80 || u[k] > 0xBF) return 0;
  return n;
}

class JsonWriter {
 public:
  JsonWriter(char* buf, uint16_t size) : buf_(buf), size_(size) {
    if (size) buf[0] = '\0';
  }

  JsonWriter& beginObject() { return open('{'); }
  JsonWriter& endObject() { return close('}'); }
  JsonWriter& beginArray() { return open('['); }
  JsonWriter& endArray() { return close(']'); }

  JsonWriter& key(const char* k) {
    comma();
    quoted(k, static_cast<uint16_t>(strlen(k)), true);
    put(':');
    afterKey_ = true;
    return *this;
  }
  // Text in UTF-8 (a name the user typed, a field of their JSON): it reads back byte for byte.
  JsonWriter& string(const char* s) { return string(s, static_cast<uint16_t>(strlen(s))); }
  JsonWriter& string(const char* s, uint16_t n) {
    comma();
    quoted(s, n, true);
    return *this;
  }
  // Text that should be printable ASCII (the Mega's lines): any other byte is damage from the
  // wire and is escaped as \u00XX, even where it happens to form UTF-8 (protocol/esp.md `line`).
  JsonWriter& ascii(const char* s, uint16_t n) {
    comma();
    quoted(s, n, false);
    return *this;
  }
  JsonWriter& number(int64_t v) {
    char t[24];
    char* p = t + sizeof t;
    *--p = 0;
    p = digits(v < 0 ? 0 - static_cast<uint64_t>(v) : static_cast<uint64_t>(v), p);
    if (v < 0) *--p = '-';
    return raw(p);
  }
  // value / 10^decimals, written with exactly `decimals` places (3 for mm, 1 for °C).
  JsonWriter& fixed(int32_t value, uint8_t decimals) {
    if (!decimals || decimals > 6) return number(value);
    uint32_t u = value < 0 ? 0u - static_cast<uint32_t>(value) : static_cast<uint32_t>(value);
    char t[24];
    char* p = t + sizeof t;
    *--p = 0;
    for (uint8_t i = 0; i < decimals; i++, u /= 10) *--p = static_cast<char>('0' + u % 10);
    *--p = '.';
    p = digits(u, p);
    if (value < 0) *--p = '-';
    return raw(p);
  }
  JsonWriter& boolean(bool b) { return raw(b ? "true" : "false"); }
  JsonWriter& null() { return raw("null"); }

  bool ok() const { return !overflow_ && depth_ == 0; }
  const char* text() const { return buf_; }
  uint16_t length() const { return len_; }

 private:
  // u's decimal digits, written to end just before `end` (no %lld: not every libc's printf has it);
  // returns where they start.
  static char* digits(uint64_t u, char* end) {
    do *--end = static_cast<char>('0' + u % 10);
    while (u /= 10);
    return end;
  }
  JsonWriter& raw(const char* t) {
    comma();
    while (*t) put(*t++);
    return *this;
  }
  JsonWriter& open(char c) {
    comma();
    put(c);
    if (depth_ < sizeof first_) first_[depth_] = true;
    depth_++;
    return *this;
  }
  JsonWriter& close(char c) {
    if (depth_) depth_--;
    put(c);
    return *this;
  }
  void comma() {
    if (afterKey_) {
      afterKey_ = false;
      return;
    }
    if (!depth_) return;
    bool& first = first_[depth_ < sizeof first_ ? depth_ - 1 : sizeof first_ - 1];
    if (!first) put(',');
    first = false;
  }
  void quoted(const char* s, uint16_t n, bool utf8) {
    put('"');
    for (uint16_t i = 0; i < n; i++) {
      unsigned char c = static_cast<unsigned char>(s[i]);
      uint8_t seq = utf8 && c >= 0x80 ? utf8Sequence(s + i, n - i) : 0;
      if (seq) {  // a whole, valid sequence: copied as it is
        for (uint8_t k = 0; k < seq; k++) put(s[i + k]);
        i = static_cast<uint16_t>(i + seq - 1);
      } else if (c == '"' || c == '\\') {
        put('\\');
        put(static_cast<char>(c));
      } else if (c < 0x20 || c >= 0x7f) {  // a control character, or a byte that is not text: visible, and the JSON stays valid
        char t[8];
        snprintf(t, sizeof t, "\\u%04x", c);
        for (char* p = t; *p; p++) put(*p);
      } else {
        put(static_cast<char>(c));
      }
    }
    put('"');
  }
  void put(char c) {
    if (overflow_) return;
    if (len_ + 1u >= size_) {  // out of room: nothing rather than a cut-off text
      overflow_ = true;
      len_ = 0;
      if (size_) buf_[0] = '\0';
      return;
    }
    buf_[len_++] = c;
    buf_[len_] = '\0';
  }

  char* buf_;
  uint16_t size_;
  uint16_t len_ = 0;
  uint8_t depth_ = 0;
  bool first_[8] = {};
  bool afterKey_ = false;
  bool overflow_ = false;
};

}  // namespace esp
}  // namespace uv
