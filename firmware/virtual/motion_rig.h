// Host tests' machine: runs the step engine's interrupt in simulated time, with endstop switches
// at given step positions, and the main loop's motion.poll() every `loopUs` (or later).
#pragma once
#include <stdint.h>

#include <functional>
#include <vector>

#include "motion.h"
#include "step_engine.h"

namespace mega {

struct StepEvent {
  uint64_t us2;  // time in half-µs ticks (the step timer's)
  uint16_t interval;  // ticks until the interrupt after this step
  uint8_t axes;
  uint8_t dirNeg;
};

// The shortest time from one X-only step to the next (ticks): how fast the head went along X.
inline uint64_t shortestXStep(const std::vector<StepEvent>& steps) {
  uint64_t shortest = UINT64_MAX;
  for (size_t i = 1; i < steps.size(); i++)
    if (steps[i].axes == 1 && steps[i - 1].axes == 1 && steps[i].us2 - steps[i - 1].us2 < shortest) shortest = steps[i].us2 - steps[i - 1].us2;
  return shortest;
}

class MotionRig {
 public:
  explicit MotionRig(const Config& c) : motion(engine, c) {}

  StepEngine engine;
  Motion motion;
  uint64_t now = 0;  // ticks (0.5 µs)
  int32_t switchAt[3] = {INT32_MIN, INT32_MIN, INT32_MIN};  // closed while position <= this
  uint32_t loopTicks = 2000;  // the main loop's period: 1 ms
  std::function<uint32_t()> loopJitter;  // extra ticks before the next main loop pass
  std::vector<StepEvent> steps;
  std::vector<uint64_t> marks;  // when a marked step went out (ticks)
  std::function<bool(uint64_t)> onMark;  // sends a scan pass's G at its step; false: the UART was busy
  bool record = true;
  bool timerOn = false;   // the step timer runs (kept between runs, like the hardware)
  uint64_t startDelayTicks = 0;  // the timer's next start comes this much later (the board's CPU still busy)
  uint64_t nextTick = 0;

  // Where the head physically is, in steps from where it stood at power-up: the pulses counted as
  // the pins see them. The firmware's own count (pos()) is reset by homing; the head stays put, and
  // its switch closed under it.
  int32_t head[3] = {0, 0, 0};

  uint8_t endstops() const {
    uint8_t bits = 0;
    for (uint8_t a = 0; a < 3; a++)
      if (head[a] <= switchAt[a]) bits |= static_cast<uint8_t>(1 << a);
    return endstopOverride ? endstopOverride(bits) : bits;
  }
  std::function<uint8_t(uint8_t)> endstopOverride;  // what the interrupt reads instead

  // Runs until the motion is idle, or `maxUs` passes; returns false on a time-out.
  bool runIdle(uint64_t maxUs = 60000000) { return runUntil([&] { return motion.idle(); }, maxUs); }

  bool runUntil(const std::function<bool()>& done, uint64_t maxUs) {
    uint64_t end = now + maxUs * 2;
    uint64_t nextLoop = now;
    while (now < end) {
      if (now >= nextLoop) {
        motion.poll();
        if (done()) return true;
        nextLoop = now + loopTicks + (loopJitter ? loopJitter() : 0);
      }
      isrUntil(nextLoop);
    }
    return false;
  }

  // Runs the step interrupt up to `ticks` (it restarts when work is queued, as the driver does),
  // leaving `now` there.
  void isrUntil(uint64_t ticks) {
    if (!timerOn && !engine.idle()) {
      timerOn = true;
      nextTick = now + startDelayTicks;
      startDelayTicks = 0;
    }
    while (timerOn && nextTick <= ticks) {
      now = nextTick;
      StepTick t = engine.tick(endstops());
      if (t.idle) {
        timerOn = false;
        break;
      }
      for (uint8_t a = 0; a < 3; a++)
        if (t.step & (1 << a)) head[a] += t.dirNeg & (1 << a) ? -1 : 1;
      if (t.step && record) steps.push_back(StepEvent{now, t.interval, t.step, t.dirNeg});
      if (t.mark) {
        marks.push_back(now);
        engine.markSent(onMark ? onMark(now) : true);
      }
      nextTick = now + t.interval;
    }
    if (ticks > now) now = ticks;
  }

  int32_t pos(uint8_t axis) const {
    int32_t p[3];
    engine.position(p);
    return p[axis];
  }
};

}  // namespace mega
