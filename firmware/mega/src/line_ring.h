// A host port's receive window: the receive interrupt writes bytes straight into line slots, and the
// main loop accepts each complete line and keeps it in its slot until it has run. So no byte is lost
// however long the main loop takes, as long as the host keeps to the window (protocol/mega.md §3).
#pragma once
#include <stdint.h>

#include "dialect_frame.h"

namespace mega {

// Each port's receive window (Cap:RX_WINDOW, mega.md §3): the lines a host may have unanswered. A window
// must cover the link's round trip, and each line of it is 104 bytes of the Mega's RAM. USB carries
// the app over Web Serial and desktop hosts, a few ms each way: 3 lines keep 99 % of the line busy at
// 2 ms one way and 94 % at 4 ms (npm run bench P1; 4 lines would give 99 % at 4 ms). The ESP's sender
// sits on a wire and reads the Mega's replies on every pass of its loop: 2 lines keep it 97 % busy at 1 ms.
constexpr uint8_t kUsbWindow = 3;
constexpr uint8_t kEspWindow = 2;

struct LineSlot {
  char text[uv::kDialectMaxLine + 1];  // NUL-terminated once complete
  uint8_t len;
  bool overflow;  // the line ran over 96 bytes; text holds its first 96
  bool dead;      // accepted but answered already (an error, a duplicate): skipped when it comes up
  int32_t n;      // its line number once accepted, -1 for a plain line
};

// A port's line slots, held by whoever owns the port (main.cpp: static).
struct LineWindow {
  LineSlot* slots;
  uint8_t size;
};
template <uint8_t N>
LineWindow lineWindow(LineSlot (&slots)[N]) {
  static_assert(N >= 1 && N <= 127, "indices run to twice the window in 8 bits");
  return {slots, N};
}

class LineRing {
 public:
  explicit LineRing(LineWindow w) : slots_(w.slots), window_(w.size) {}
  uint8_t window() const { return window_; }

  // --- receive interrupt ---
  void received(char c);
  // Bytes dropped because every slot was taken (a host that ignored the window).
  uint16_t dropped() const { return dropped_; }

  // --- main loop ---
  // The oldest complete line not yet accepted, or nullptr.
  LineSlot* arrived() { return accept_ != fill_ ? &slot(accept_) : nullptr; }
  // Moves it into the run queue (dead: it needs no run, only its turn to be freed).
  void accepted(bool dead);
  // The oldest accepted line still to run, or nullptr; dead ones are freed on the way.
  LineSlot* front();
  void pop() { head_ = after(head_); }
  uint8_t queued() const { return between(head_, accept_); }
  // Slots neither holding a complete line nor queued: what the B field reports.
  uint8_t free() const { return static_cast<uint8_t>(window_ - between(head_, fill_)); }

 private:
  // Indices run from 0 to twice the window, so a full ring and an empty one differ; the window need
  // not be a power of two, and nothing here divides (the receive interrupt runs it every byte).
  uint8_t after(uint8_t i) const { return i + 1 == 2 * window_ ? 0 : static_cast<uint8_t>(i + 1); }
  uint8_t between(uint8_t from, uint8_t to) const { return static_cast<uint8_t>(to >= from ? to - from : to + 2 * window_ - from); }
  LineSlot& slot(uint8_t i) { return slots_[i < window_ ? i : i - window_]; }

  LineSlot* const slots_;
  const uint8_t window_;
  volatile uint8_t head_ = 0, accept_ = 0, fill_ = 0;
  uint8_t len_ = 0;
  bool overflow_ = false;
  bool noSlot_ = false;  // the line being received has nowhere to go
  uint16_t dropped_ = 0;
};

}  // namespace mega
