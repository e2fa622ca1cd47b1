// Splits a byte stream into newline-terminated lines with a length limit (both serial links).
#include "line_splitter.h"

namespace uv {

bool LineSplitter::push(char c) {
  if (c == '\n') {
    uint8_t n = len_;
    if (n > 0 && buf_[n - 1] == '\r') n--;
    doneOverflow_ = overflow_ || n > max_;
    done_ = n > max_ ? max_ : n;
    buf_[done_] = '\0';
    len_ = 0;
    overflow_ = false;
    return true;
  }
  if (len_ <= max_) {
    buf_[len_++] = c;  // one spare byte so a final '\r' still fits
  } else {
    overflow_ = true;
  }
  return false;
}

bool isPrintable(const char* text, uint8_t len) {
  for (uint8_t i = 0; i < len; i++) {
    uint8_t c = static_cast<uint8_t>(text[i]);
    if (c < 0x20 || c > 0x7e) return false;
  }
  return true;
}

}  // namespace uv
