// Splits a byte stream into newline-terminated lines with a length limit (both serial links).
#pragma once
#include <stdint.h>

namespace uv {

// The caller owns the buffer, which must hold maxLine + 1 bytes (room for a final '\r').
class LineSplitter {
 public:
  LineSplitter(char* buffer, uint8_t maxLine) : buf_(buffer), max_(maxLine) {}

  // Feeds one byte. Returns true when it completed a line; read it with text()/length()
  // and overflow() before the next push. One '\r' before '\n' is dropped.
  bool push(char c);

  const char* text() const { return buf_; }
  uint8_t length() const { return done_; }
  // The line was longer than maxLine; text() holds its first maxLine bytes.
  bool overflow() const { return doneOverflow_; }
  uint8_t pending() const { return len_; }
  void reset() { len_ = 0; overflow_ = false; }

 private:
  char* buf_;
  uint8_t max_;
  uint8_t len_ = 0;
  uint8_t done_ = 0;
  bool overflow_ = false;
  bool doneOverflow_ = false;
};

// True when every byte is printable ASCII (0x20-0x7E).
bool isPrintable(const char* text, uint8_t len);

}  // namespace uv
