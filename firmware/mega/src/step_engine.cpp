// The step interrupt's work, as plain C++: segments, Bresenham, position and endstop seeks.
#include "step_engine.h"

#include "atomic.h"

namespace mega {

uint8_t StepEngine::pushBlock(const StepBlock& b) {
  uint8_t slot = blockHead_ % kBlocks;
  blocks_[slot] = b;
  ended_[slot] = false;
  UV_ATOMIC { blockHead_ = static_cast<uint8_t>(blockHead_ + 1); }
  return slot;
}

bool StepEngine::pushSegment(uint8_t slot, uint16_t steps, uint16_t interval, bool last, uint16_t frac, bool mark) {
  static_assert(kBlocks <= kSlotBits + 1, "a slot fits its bits");
  bool pushed = false;
  const uint8_t flags = static_cast<uint8_t>(slot | (last ? kLast : 0) | (mark ? kMark : 0));
  UV_ATOMIC {
    if (!ended_[slot]) {
      segs_[segHead_ % kSegments] = QueuedSegment{steps, interval, frac, flags};
      segHead_ = static_cast<uint8_t>(segHead_ + 1);
      pushed = true;
    }
  }
  return pushed;
}

void StepEngine::halt() {
  UV_ATOMIC {
    segTail_ = segHead_;
    blockTail_ = blockHead_;
    running_ = false;
    segLeft_ = 0;
    curSlot_ = 0xff;
    for (bool& e : ended_) e = true;
  }
}

StepEngine::Cut StepEngine::cutAfterCurrent() {
  Cut c{};
  UV_ATOMIC {
    c.running = curSlot_ != 0xff;  // a block under way, maybe between two of its segments
    c.slot = curSlot_;
    c.done = blockDone_ + segLeft_;
    c.interval = lastInterval_;
    if (segLeft_ > 0) {
      segHead_ = static_cast<uint8_t>(segTail_ + 1);  // if it is the block's last, the block ends with it
    } else {
      segHead_ = segTail_;
    }
  }
  return c;
}

void StepEngine::dropBlocksAfter(uint8_t slot) {
  UV_ATOMIC {
    // The running block sits at blockTail_; blocks behind it have no segment running.
    if (blockCount() && blockTail_ % kBlocks == slot) {
      blockHead_ = static_cast<uint8_t>(blockTail_ + 1);
    } else {
      blockHead_ = blockTail_;
    }
  }
}

bool StepEngine::idle() const {
  bool idle;
  UV_ATOMIC { idle = !running_ && segHead_ == segTail_ && blockHead_ == blockTail_; }
  return idle;
}

void StepEngine::position(int32_t out[3]) const {
  UV_ATOMIC {
    for (uint8_t a = 0; a < 3; a++) out[a] = pos_[a];
  }
}

void StepEngine::setPosition(const int32_t steps[3]) {
  UV_ATOMIC {
    for (uint8_t a = 0; a < 3; a++) pos_[a] = steps[a];
  }
}

void StepEngine::finishBlock() {
  ended_[curSlot_] = true;
  blockTail_ = static_cast<uint8_t>(blockTail_ + 1);
  curSlot_ = 0xff;
}

bool StepEngine::loadSegment(StepTick& t) {
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

void StepEngine::endSeek() {
  seekHit_ = true;
  seekSteps_ = blockDone_;
  // Drop this block's queued segments; pushSegment refuses any more for it.
  while (segHead_ != segTail_ && (segs_[segTail_ % kSegments].flags & kSlotBits) == curSlot_) segTail_ = static_cast<uint8_t>(segTail_ + 1);
  segLeft_ = 0;
  running_ = false;
  finishBlock();
}

void StepEngine::endSegment() {
  segTail_ = static_cast<uint8_t>(segTail_ + 1);
  if (lastSegment_) {
    if (seekMask_) seekSteps_ = blockDone_;
    finishBlock();
  }
}

// The hot path runs every step: no loops, no shifts by a variable, the block's numbers in scalars.
StepTick StepEngine::tick(uint8_t endstops) {
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
