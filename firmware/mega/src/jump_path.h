// A flown blank stretch inside a scan stroke (issue 19, planner.md "Blank stretches"): the head
// leaves the pass's speed, speeds up, cruises, slows down and is back at the speed, over exactly
// `steps` steps in exactly `ticks` timer ticks, so every window after it is where the Nano's program
// puts it. The main loop cuts it into the step interrupt's segments from the time at which the head
// reaches each step; floats are fine there (never in the interrupt).
#pragma once
#include <stdint.h>

namespace mega {

class JumpPath {
 public:
  // `rate`: the pass's speed, steps per tick; `accel`: the axis's, steps per tick². A stretch the
  // planner flies always has room for its speed-up, but with rounding the time may be a hair short
  // of what `accel` allows: then the path takes the acceleration it needs (accel() says which).
  void plan(uint32_t steps, uint32_t ticks, float rate, float accel);
  // Ticks from the stretch's start until the head reaches step x (0 ≤ x ≤ steps): 0 at 0 and
  // exactly `ticks` at `steps`, rising in between.
  float at(uint32_t x) const;
  uint32_t steps() const { return n_; }
  uint32_t ticks() const { return j_; }
  float peak() const { return v_ + a_ * t1_; }  // steps per tick
  float accel() const { return a_; }             // steps per tick²

 private:
  float lead(float x) const;  // ticks to cover x steps from the speed while speeding up
  // The Mega holds one while a stroke runs: only what the rest is computed from. With a_ = 0 the
  // path is one speed, v_.
  uint32_t n_ = 0, j_ = 0;
  float v_ = 0, a_ = 0, t1_ = 0;  // the speed, the acceleration, the speed-up's ticks
};

}  // namespace mega
