// The step interrupt's work, as plain C++: segments, Bresenham, position and endstop seeks.
#include "step_engine.h"

#include "atomic.h"

namespace mega {

uint8_t StepEngine::pushBlock(const StepBlock& b) {
  uint8_t slot = blockHead_ % kBlocks;
  blocks_[slot] = b;
  UV_ATOMIC {
    ended_ = static_cast<uint8_t>(ended_ & ~(1u << slot));
    blockHead_ = static_cast<uint8_t>(blockHead_ + 1);
  }
  return slot;
}

bool StepEngine::pushSegment(uint8_t slot, uint16_t steps, uint16_t interval, bool last, uint16_t frac, bool mark) {
  static_assert(kBlocks <= kSlotBits + 1, "a slot fits its bits");
  bool pushed = false;
  const uint8_t flags = static_cast<uint8_t>(slot | (last ? kLast : 0) | (mark ? kMark : 0));
  UV_ATOMIC {
    if (!(ended_ & (1u << slot))) {
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
    ended_ = 0xff;
    glide_.left = 0;
    blockDue_ = glideDue_ = 0;
  }
}

bool StepEngine::blocksMove(uint8_t axis) const {
  uint8_t tail;
  UV_ATOMIC { tail = blockTail_; }
  for (uint8_t i = tail; i != blockHead_; i++)
    if (blocks_[i % kBlocks].steps[axis]) return true;
  return false;
}

void StepEngine::startGlide(const uv::Glide& g, bool negative) {
  UV_ATOMIC {
    glide_ = g;
    glideNeg_ = negative;
    glideDue_ = g.interval;  // its first step that long after the next call
    blockDue_ = 0;           // which runs the blocks' step, if one is due
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
  UV_ATOMIC { idle = !running_ && segHead_ == segTail_ && blockHead_ == blockTail_ && !glide_.left; }
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

// A glide beside the blocks (or alone): each call takes whichever steps are due, and the next
// comes at the sooner of the two. Once the glide has ended, the blocks' step still waits out its time.
StepTick StepEngine::tickGliding(uint8_t endstops) {
  StepTick t{0, dirNeg_, false, 0, false, false};
  if (blockDue_ == kNoStep && segHead_ != segTail_) blockDue_ = 0;  // a block queued meanwhile starts now
  if (blockDue_ == 0) {
    t = tickBlocks(endstops);
    blockDue_ = t.idle ? kNoStep : t.interval;
    t.idle = false;
  }
  if (glide_.left) {
    t.dirNeg = static_cast<uint8_t>(glideNeg_ ? t.dirNeg | 2 : t.dirNeg & ~2);
    if (glideDue_ == 0) {
      t.step |= 2;
      pos_[1] += glideNeg_ ? -1 : 1;
      if (--glide_.left) glideDue_ = glide_.interval = uv::glideNext(glide_);
    }
  }
  uint16_t next = blockDue_;
  if (glide_.left && glideDue_ < next) next = glideDue_;
  if (next == kNoStep) {  // both done: a step now is the glide's last, its pulse ends at the next call
    blockDue_ = 0;
    if (!t.step) t.idle = true;
    t.interval = kGlideTail;
    return t;
  }
  if (blockDue_ != kNoStep) blockDue_ = static_cast<uint16_t>(blockDue_ - next);
  if (glide_.left) glideDue_ = static_cast<uint16_t>(glideDue_ - next);
  t.interval = next;
  return t;
}

}  // namespace mega
