// The step interrupt's work, as plain C++: it takes queued segments, runs Bresenham over X, Y and Z,
// counts the position, and ends a seek (homing, self-test) when its endstop closes. The main loop
// queues blocks and segments; hw/stepper_timer calls tick() from the timer and drives the pins.
#pragma once
#include <stdint.h>

namespace mega {

struct StepBlock {
  uint32_t steps[3];  // per axis, absolute; the most of the three is the dominant axis's
  uint8_t dirNeg;     // bit a: axis a moves towards −
  int8_t seekAxis;    // −1, or the axis whose endstop ends this block early
};

struct StepTick {
  uint8_t step;       // bit a: pulse axis a's step pin
  uint8_t dirNeg;     // the direction pins for these steps
  bool dirChanged;    // the direction pins changed: wait their setup time before the pulse
  uint16_t interval;  // ticks until the next call
  bool idle;          // nothing to run: the timer may stop
  bool mark;          // this step starts a marked segment: send the printhead its G now (markSent())
};

class StepEngine {
 public:
  static constexpr uint8_t kBlocks = 8;     // the motion queue (the `P` of every ok)
  static constexpr uint8_t kSegments = 16;  // 16 × 2.5 ms: the main loop may be 40 ms late

  // --- main loop side ---
  // Blocks ever queued, mod 256: the next block's sequence number (its slot is that mod kBlocks).
  uint8_t blockHead() const { return blockHead_; }
  uint8_t blocksFree() const { return static_cast<uint8_t>(kBlocks - blockCount()); }
  // Returns the block's slot. Only when blocksFree().
  uint8_t pushBlock(const StepBlock& b);
  bool segmentFree() const { return static_cast<uint8_t>(segHead_ - segTail_) < kSegments; }
  // Queues a segment of block `slot` unless that block was ended early (a seek that hit its
  // endstop); `last` marks the block's final segment. Returns false if the block has ended.
  // `frac`: a further frac/65536 tick per step, carried from step to step through the block, so a
  // constant speed is exact over a whole pass rather than rounded to whole ticks. `mark`: the
  // segment's first step is the one a scan pass's G goes out with (StepTick::mark).
  bool pushSegment(uint8_t slot, uint16_t steps, uint16_t interval, bool last, uint16_t frac = 0, bool mark = false);
  // Stops at once: every queued segment and block is dropped. Steps may be lost at speed.
  void halt();
  // Keeps the running segment and drops the ones queued after it; returns where the running
  // block will be once that segment is done, for a controlled stop.
  struct Cut {
    bool running;
    uint8_t slot;
    uint32_t done;   // dominant-axis steps of the block done when the running segment ends
    uint16_t interval;
  };
  Cut cutAfterCurrent();
  // Drops every block after `slot`, and `slot` itself if it has no segment running.
  void dropBlocksAfter(uint8_t slot);
  bool idle() const;
  void position(int32_t out[3]) const;
  void setPosition(const int32_t steps[3]);
  // The last seek's result: whether its endstop closed, after how many dominant steps.
  bool seekHit() const { return seekHit_; }
  uint32_t seekSteps() const { return seekSteps_; }
  bool blockEnded(uint8_t slot) const { return ended_[slot]; }
  // Times the interrupt found no segment in the middle of a block (the main loop was late).
  uint16_t underruns() const { return underruns_; }
  // Marks reached, and of those how many found the printhead's UART busy so their G could not go
  // out on time (the interrupt's driver reports each through markSent()).
  uint8_t marks() const { return marks_; }
  uint8_t marksMissed() const { return marksMissed_; }

  // --- interrupt side ---
  // endstops: bit a set while axis a's endstop is closed.
  StepTick tick(uint8_t endstops);
  void markSent(bool onTime) {
    marks_++;
    if (!onTime) marksMissed_++;
  }

 private:
  uint8_t blockCount() const { return static_cast<uint8_t>(blockHead_ - blockTail_); }
  void finishBlock();
  // The interrupt's colder paths, once a segment or a block.
  bool loadSegment(StepTick& t);
  void endSegment();
  void endSeek();

  struct QueuedSegment {
    uint16_t steps, interval, frac;
    uint8_t flags;  // the block's slot, kLast, kMark
  };
  static constexpr uint8_t kSlotBits = 0x0f, kLast = 0x40, kMark = 0x80;

  // The queues index with free-running 8-bit counters: their sizes must divide 256.
  static_assert((kBlocks & (kBlocks - 1)) == 0 && (kSegments & (kSegments - 1)) == 0, "ring sizes must be powers of two");
  StepBlock blocks_[kBlocks];
  bool ended_[kBlocks] = {};
  QueuedSegment segs_[kSegments];
  volatile uint8_t blockHead_ = 0, blockTail_ = 0;  // free-running; slot = index % kBlocks
  volatile uint8_t segHead_ = 0, segTail_ = 0;
  // The running segment and block (interrupt side), copied out of the queues so each step reads
  // plain members.
  bool running_ = false;
  bool lastSegment_ = false;
  uint16_t segLeft_ = 0;
  uint16_t interval_ = 0;
  uint16_t frac_ = 0, fracAcc_ = 0;  // the running segment's fraction, and what it has carried
  uint8_t curSlot_ = 0xff;
  uint8_t seekMask_ = 0;
  uint32_t total_ = 0, steps0_ = 0, steps1_ = 0, steps2_ = 0;
  uint32_t err0_ = 0, err1_ = 0, err2_ = 0;
  uint32_t blockDone_ = 0;
  uint8_t dirNeg_ = 0;
  uint8_t debounce_ = 0;
  uint16_t lastInterval_ = 0;
  uint16_t underruns_ = 0;
  volatile uint8_t marks_ = 0, marksMissed_ = 0;
  int32_t pos_[3] = {};
  bool seekHit_ = false;
  uint32_t seekSteps_ = 0;
};

}  // namespace mega
