// A JSON writer into a caller's buffer, for the ESP's live messages and status: no heap, commas
// placed by itself, strings escaped. The bridge core writes JSON on the host too, where
// ArduinoJson is not available; parsing stays with the JSON libraries (print_request.h's views).
#pragma once
#include <stdint.h>
#include <stdio.h>
#include <string.h>

namespace uv {
namespace esp {

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
    quoted(k, static_cast<uint16_t>(strlen(k)));
    put(':');
    afterKey_ = true;
    return *this;
  }
  JsonWriter& string(const char* s) { return string(s, static_cast<uint16_t>(strlen(s))); }
  JsonWriter& string(const char* s, uint16_t n) {
    comma();
    quoted(s, n);
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
  void quoted(const char* s, uint16_t n) {
    put('"');
    for (uint16_t i = 0; i < n; i++) {
      unsigned char c = static_cast<unsigned char>(s[i]);
      if (c == '"' || c == '\\') {
        put('\\');
        put(static_cast<char>(c));
      } else if (c < 0x20 || c >= 0x7f) {  // a damaged byte from the wire: keep it visible, keep the JSON valid
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
    if (len_ + 1u >= size_) {
      overflow_ = true;
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
