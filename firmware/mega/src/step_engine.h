// The step interrupt's work, as plain C++: it takes queued segments, runs Bresenham over X, Y and Z,
// counts the position, and ends a seek (homing, self-test) when its endstop closes; beside the
// blocks it runs a glide, Y steps on their own timing (glide.h). The main loop queues blocks and
// segments; hw/stepper_timer calls tickBlocks() or tickGliding() from the timer and drives the pins.
#pragma once
#include <stdint.h>

#include "glide.h"

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
  // Starts a glide (glide.h): Y steps from rest to rest on their own timing, beside the running
  // block's (a scan stroke's run-out, X alone) or alone, towards − if `negative`. Only while no
  // block queued or running moves Y, and no glide runs. Ends with the next halt() too.
  void startGlide(const uv::Glide& g, bool negative);
  bool gliding() const { return glide_.left != 0; }
  // Stops at once: every queued segment and block, and the glide, are dropped. Steps may be lost at speed.
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
  bool blockEnded(uint8_t slot) const { return ended_ & (1u << slot); }
  // Whether a block queued or running moves `axis`.
  bool blocksMove(uint8_t axis) const;
  // Times the interrupt found no segment in the middle of a block (the main loop was late).
  uint16_t underruns() const { return underruns_; }
  // Marks reached, and of those how many found the printhead's UART busy so their G could not go
  // out on time (the interrupt's driver reports each through markSent()).
  uint8_t marks() const { return marks_; }
  uint8_t marksMissed() const { return marksMissed_; }

  // --- interrupt side ---
  // endstops: bit a set while axis a's endstop is closed. tick() takes whichever of the two below is
  // live; the board's interrupt makes that choice itself, so its usual path is tickBlocks() with its
  // colder paths inlined whole, as when tick() was one function. (Called from two places, they went
  // out of line and the tick to the stack: the longest step interrupt went from 41 to 55 µs and a
  // fast move underran in simavr. Inlined, 43 µs.)
  StepTick tick(uint8_t endstops) { return twoTimings() ? tickGliding(endstops) : tickBlocks(endstops); }
  // A glide runs, or the blocks' step still waits out the time the glide left it.
  bool twoTimings() const { return glide_.left || blockDue_; }
  // The blocks' own step, the hot path; and the tick while a glide runs beside them (out of line).
  inline StepTick tickBlocks(uint8_t endstops) __attribute__((always_inline));
  StepTick tickGliding(uint8_t endstops) __attribute__((noinline));
  void markSent(bool onTime) {
    marks_++;
    if (!onTime) marksMissed_++;
  }

 private:
  uint8_t blockCount() const { return static_cast<uint8_t>(blockHead_ - blockTail_); }
  inline void finishBlock() __attribute__((always_inline));
  // The interrupt's colder paths, once a segment or a block.
  inline bool loadSegment(StepTick& t) __attribute__((always_inline));
  inline void endSegment() __attribute__((always_inline));
  inline void endSeek() __attribute__((always_inline));

  struct QueuedSegment {
    uint16_t steps, interval, frac;
    uint8_t flags;  // the block's slot, kLast, kMark
  };
  static constexpr uint8_t kSlotBits = 0x0f, kLast = 0x40, kMark = 0x80;

  // The queues index with free-running 8-bit counters: their sizes must divide 256.
  static_assert((kBlocks & (kBlocks - 1)) == 0 && (kSegments & (kSegments - 1)) == 0, "ring sizes must be powers of two");
  StepBlock blocks_[kBlocks];
  uint8_t ended_ = 0;  // bit `slot`: the block in it has ended (or was dropped)
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
  // The glide and the two timings it brings: ticks from the next call to each one's next step (the
  // blocks' kNoStep when none runs). Both 0 when no glide runs.
  static constexpr uint16_t kNoStep = 0xFFFF;  // over any interval (kMinStepRate: 62500 ticks)
  static constexpr uint16_t kGlideTail = 100;  // after a glide's last step, when nothing else runs
  uv::Glide glide_ = {};
  bool glideNeg_ = false;
  uint16_t blockDue_ = 0, glideDue_ = 0;
};

// The interrupt's colder paths and its hot one, here so that the board's interrupt inlines them all
// (as it did when tick() was one function in one file).
inline void StepEngine::finishBlock() {
  ended_ = static_cast<uint8_t>(ended_ | (1u << curSlot_));
  blockTail_ = static_cast<uint8_t>(blockTail_ + 1);
  curSlot_ = 0xff;
}

inline bool StepEngine::loadSegment(StepTick& t) {
  if (segHead_ == segTail_) {
    if (curSlot_ != 0xff) underruns_++;  // the main loop fell behind mid-block: must never happen
    running_ = false;
    t.idle = true;
    return false;
  }
  const QueuedSegment& s = segs_[segTail_ % kSegments];
  const uint8_t slot = s.flags & kSlotBits;
  if (slot != curSlot_) {  // a new block: Bresenham from the middle, new directions
    curSlot_ = slot;
    fracAcc_ = 0;
    const StepBlock& b = blocks_[curSlot_];
    steps0_ = b.steps[0];
    steps1_ = b.steps[1];
    steps2_ = b.steps[2];
    total_ = steps0_ > steps1_ ? steps0_ : steps1_;
    if (steps2_ > total_) total_ = steps2_;
    err0_ = err1_ = err2_ = total_ / 2;
    blockDone_ = 0;
    debounce_ = 0;
    t.dirChanged = b.dirNeg != dirNeg_;
    dirNeg_ = b.dirNeg;
    t.dirNeg = dirNeg_;
    seekMask_ = b.seekAxis >= 0 ? static_cast<uint8_t>(1 << b.seekAxis) : 0;
    if (seekMask_) {
      seekHit_ = false;
      seekSteps_ = 0;
    }
  }
  segLeft_ = s.steps;
  interval_ = s.interval;
  frac_ = s.frac;
  lastInterval_ = s.interval;
  lastSegment_ = s.flags & kLast;
  t.mark = s.flags & kMark;
  running_ = true;
  return true;
}

inline void StepEngine::endSeek() {
  seekHit_ = true;
  seekSteps_ = blockDone_;
  // Drop this block's queued segments; pushSegment refuses any more for it.
  while (segHead_ != segTail_ && (segs_[segTail_ % kSegments].flags & kSlotBits) == curSlot_) segTail_ = static_cast<uint8_t>(segTail_ + 1);
  segLeft_ = 0;
  running_ = false;
  finishBlock();
}

inline void StepEngine::endSegment() {
  segTail_ = static_cast<uint8_t>(segTail_ + 1);
  if (lastSegment_) {
    if (seekMask_) seekSteps_ = blockDone_;
    finishBlock();
  }
}

// The hot path runs every step (here, so the board's interrupt inlines it): no loops, no shifts by
// a variable, the block's numbers in scalars.
inline StepTick StepEngine::tickBlocks(uint8_t endstops) {
  StepTick t{0, dirNeg_, false, 0, false, false};
  if (segLeft_ == 0 && !loadSegment(t)) return t;
  t.interval = interval_;
  if (frac_) {
    const uint16_t acc = static_cast<uint16_t>(fracAcc_ + frac_);
    if (acc < fracAcc_) t.interval++;  // the fraction carried a whole tick
    fracAcc_ = acc;
  }
  if (endstops & seekMask_) {
    // Closed: confirm with a second reading one interval later, without stepping, so the
    // position where the seek ends is exactly where the switch closed.
    if (debounce_ == 0) {
      debounce_ = 1;
      return t;
    }
    endSeek();
    return t;
  }
  debounce_ = 0;
  uint8_t step = 0;
  if ((err0_ += steps0_) >= total_) {
    err0_ -= total_;
    step |= 1;
    pos_[0] += (dirNeg_ & 1) ? -1 : 1;
  }
  if ((err1_ += steps1_) >= total_) {
    err1_ -= total_;
    step |= 2;
    pos_[1] += (dirNeg_ & 2) ? -1 : 1;
  }
  if ((err2_ += steps2_) >= total_) {
    err2_ -= total_;
    step |= 4;
    pos_[2] += (dirNeg_ & 4) ? -1 : 1;
  }
  t.step = step;
  blockDone_++;
  if (--segLeft_ == 0) endSegment();
  return t;
}

}  // namespace mega
