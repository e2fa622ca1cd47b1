// What the LEDs got (protocol/nano.md "Dose records"): each LED's on-time per F and per scan program,
// from the events the timer carried out up to the end or the cut, queued for the Mega's `O` polls.
// Plain C++ in the main loop, tested on the host: the timer pays nothing for it between two edges.
#pragma once
#include <stdint.h>

#include "nano_codec.h"

namespace nano {

struct DoseRecord {
  uint32_t exposure;  // as C counts it: 1 the first since start
  uint16_t program;   // place in its chain, 0 first; 0 for an F
  uint32_t onUs[uv::kLedCount];
};

class DoseTally {
 public:
  // Records that wait for an `O` (the Nano's RAM is at its 50 % budget). The Mega asks after every
  // Q poll while a chain runs, every 20 ms at most, and a chain cannot run programs faster than the
  // link loads them into its two buffers (about 16 ms for 64 events at 115200).
  static constexpr uint8_t kRecords = 2;
  static constexpr uint32_t kWhole = 0xFFFFFFFFu;  // `untilUs` of an exposure that ran its full time

  // An exposure starts, every LED dark: an F (one record) or a chain (one per program).
  void begin(uint32_t exposure) {
    exposure_ = exposure;
    program_ = 0;
    lights_ = 0;
  }
  // An F's record is opened as it lights, with each lit LED's duration, and closed when it has gone
  // dark: whole, or cut `untilUs` after its on-edge (no LED then keeps more than that).
  void openFire(const uv::NanoCommand& f);
  bool fireOpen() const { return fireOpen_; }
  void closeFire(uint32_t untilUs);
  // The chain's next program, its events as the store keeps them (d × 16 + m), run until `untilUs`
  // after its time 0 (the previous program's last event; the G's time 0 for the first): kWhole when
  // it ran to its last event. An LED lit across a program's end counts in the program it is lit in.
  void program(const uint32_t* words, uint8_t count, uint32_t untilUs);
  // The oldest record not yet reported, dropped from the queue as it is taken.
  bool take(DoseRecord& out);
  uint8_t waiting() const { return count_; }

 private:
  void keep(const uint32_t onUs[uv::kLedCount]);  // queues the record, numbered, if there is room
  DoseRecord& next() { return queue_[(first_ + count_) % kRecords]; }

  DoseRecord queue_[kRecords] = {};
  uint8_t first_ = 0, count_ = 0;
  uint32_t exposure_ = 0;
  uint16_t program_ = 0;
  uint8_t lights_ = 0;  // the chain's LED state at the end of the last program tallied
  bool fireOpen_ = false;  // an F's record waits, unqueued, in next() for the F to go dark
};

}  // namespace nano
