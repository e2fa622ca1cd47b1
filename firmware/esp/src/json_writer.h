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
    uint64_t u = v < 0 ? 0 - static_cast<uint64_t>(v) : static_cast<uint64_t>(v);  // no %lld: not every libc's printf has it
    do *--p = static_cast<char>('0' + u % 10);
    while (u /= 10);
    if (v < 0) *--p = '-';
    return raw(p);
  }
  // value / 10^decimals, written with exactly `decimals` places (3 for mm, 1 for °C).
  JsonWriter& fixed(int32_t value, uint8_t decimals) {
    if (!decimals || decimals > 6) return number(value);
    int64_t scale = 1;
    for (uint8_t i = 0; i < decimals; i++) scale *= 10;
    int64_t v = value;
    bool negative = v < 0;
    if (negative) v = -v;
    char t[32];
    int n = 0;
    if (negative) t[n++] = '-';
    char whole[24];
    char* p = whole + sizeof whole;
    *--p = 0;
    int64_t w = v / scale;
    do *--p = static_cast<char>('0' + w % 10);
    while (w /= 10);
    while (*p) t[n++] = *p++;
    t[n++] = '.';
    int64_t frac = v % scale;
    for (int64_t d = scale / 10; d >= 1; d /= 10) t[n++] = static_cast<char>('0' + frac / d % 10);
    t[n] = 0;
    comma();
    for (char* c = t; *c; c++) put(*c);
    return *this;
  }
  JsonWriter& boolean(bool b) { return raw(b ? "true" : "false"); }
  JsonWriter& null() { return raw("null"); }

  bool ok() const { return !overflow_ && depth_ == 0; }
  const char* text() const { return buf_; }
  uint16_t length() const { return len_; }

 private:
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
