// Reads a file line by line through a small buffer, without a heap.
#include "storage.h"

namespace mega {

bool LineReader::fill() {
  if (eof_) return false;
  int16_t n = sd_.read(f_, buf_, sizeof buf_);
  if (n <= 0) {
    eof_ = true;
    failed_ = n < 0;
    return false;
  }
  pos_ = 0;
  end_ = static_cast<uint8_t>(n);
  return true;
}

bool LineReader::next(char* out, uint8_t max, uint8_t& len, bool& tooLong) {
  len = 0;
  tooLong = false;
  bool any = false;
  for (;;) {
    if (pos_ == end_ && !fill()) break;
    any = true;
    char c = buf_[pos_++];
    if (c == '\n') break;
    if (len < max) out[len++] = c;
    else tooLong = true;
  }
  if (len && out[len - 1] == '\r') len--;
  out[len] = 0;
  return any;
}

}  // namespace mega
