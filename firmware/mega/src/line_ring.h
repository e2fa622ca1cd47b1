// A host port's receive window: the receive interrupt writes bytes straight into line slots, and the
// main loop accepts each complete line and keeps it in its slot until it has run. So no byte is lost
// however long the main loop takes, as long as the host keeps to the window (protocol/mega.md §3).
#pragma once
#include <stdint.h>

#include "dialect_frame.h"

namespace mega {

// Each port's receive window (Cap:RX_WINDOW, mega.md §3): the lines a host may have unanswered. A window
// must cover the link's round trip. USB carries the app over Web Serial and desktop hosts, a few ms
// each way (npm run bench P1: 4 lines keep 99 % of the line busy at 4 ms one-way, 3 lines 94 %). The
// ESP's sender sits on a wire and reads the Mega's replies every pass of its loop: 2 lines keep it
// 97 % busy at 1 ms, and each line less is 104 bytes of the Mega's RAM.
constexpr uint8_t kUsbWindow = 4;
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
  static_assert(N && (N & (N - 1)) == 0, "free-running 8-bit indices: the window must divide 256");
  return {slots, N};
}

class LineRing {
 public:
  explicit LineRing(LineWindow w) : slots_(w.slots), mask_(static_cast<uint8_t>(w.size - 1)) {}
  uint8_t window() const { return static_cast<uint8_t>(mask_ + 1); }

  // --- receive interrupt ---
  void received(char c);
  // Bytes dropped because every slot was taken (a host that ignored the window).
  uint16_t dropped() const { return dropped_; }

  // --- main loop ---
  // The oldest complete line not yet accepted, or nullptr.
  LineSlot* arrived() { return accept_ != fill_ ? &slots_[accept_ & mask_] : nullptr; }
  // Moves it into the run queue (dead: it needs no run, only its turn to be freed).
  void accepted(bool dead);
  // The oldest accepted line still to run, or nullptr; dead ones are freed on the way.
  LineSlot* front();
  void pop() { head_ = static_cast<uint8_t>(head_ + 1); }
  uint8_t queued() const { return static_cast<uint8_t>(accept_ - head_); }
  // Slots neither holding a complete line nor queued: what the B field reports.
  uint8_t free() const { return static_cast<uint8_t>(window() - static_cast<uint8_t>(fill_ - head_)); }

 private:
  LineSlot* const slots_;
  const uint8_t mask_;  // the window less one: slot = index & mask_
  volatile uint8_t head_ = 0, accept_ = 0, fill_ = 0;  // free-running
  uint8_t len_ = 0;
  bool overflow_ = false;
  bool noSlot_ = false;  // the line being received has nowhere to go
  uint16_t dropped_ = 0;
};

}  // namespace mega
