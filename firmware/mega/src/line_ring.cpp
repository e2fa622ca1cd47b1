// A host port's receive window, filled from the receive interrupt.
#include "line_ring.h"

namespace mega {

void LineRing::received(char c) {
  bool full = between(head_, fill_) >= window_;
  if (c == '\n') {
    if (noSlot_ || full) {
      noSlot_ = false;
      dropped_++;
      len_ = 0;
      overflow_ = false;
      return;
    }
    LineSlot& s = slot(fill_);
    if (len_ && s.text[len_ - 1] == '\r') len_--;
    if (len_ == 0 && !overflow_) return;  // an empty line gets no reply at all
    s.text[len_] = 0;
    s.len = len_;
    s.overflow = overflow_;
    s.dead = false;
    len_ = 0;
    overflow_ = false;
    fill_ = after(fill_);
    return;
  }
  if (full && len_ == 0) noSlot_ = true;
  if (noSlot_) {
    dropped_++;
    return;
  }
  if (overflow_) return;  // the rest of an overlong line: only its '\n' matters
  char* text = slot(fill_).text;
  if (len_ < uv::kDialectMaxLine) {
    text[len_++] = c;
  } else if (len_ == uv::kDialectMaxLine && c == '\r') {
    text[len_++] = c;  // a final '\r' may follow a full line
  } else {
    overflow_ = true;  // text keeps the first 96 bytes
    len_ = uv::kDialectMaxLine;
  }
}

void LineRing::accepted(bool dead) {
  slot(accept_).dead = dead;
  accept_ = after(accept_);
}

LineSlot* LineRing::front() {
  while (head_ != accept_) {
    LineSlot& s = slot(head_);
    if (!s.dead) return &s;
    pop();
  }
  return nullptr;
}

}  // namespace mega
