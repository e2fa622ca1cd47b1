// Homing on the endstops (G28): per axis, Z first, a fast seek, an exact back-off, and a slow seek
// whose closing point becomes 0. Runs from the main loop, one motion at a time, never waiting.
#pragma once
#include <stdint.h>

#include "config.h"
#include "motion.h"

namespace mega {

constexpr int32_t kHomeBackoffUm = 2000;  // away from the switch between the two seeks
constexpr int32_t kHomeSlowDivisor = 10;  // the slow seek's speed: speed.home / 10

enum class RoutineStatus : uint8_t { Idle, Running, Done, Failed };

class Homing {
 public:
  Homing(Motion& motion, const Config& config) : m_(motion), c_(config) {}

  // axes: bit 0 X, 1 Y, 2 Z. Homes Z, then X, then Y.
  void start(uint8_t axes);
  // endstops: bit a set while axis a's switch is closed (read by the main loop).
  RoutineStatus poll(uint8_t endstops);
  void cancel() { phase_ = Phase::Idle; }
  // Axes homed by the last run, and the axis that failed.
  uint8_t homed() const { return homed_; }
  uint8_t failedAxis() const { return axis_; }
  // Why it failed: 44 (no switch found, or it stays closed after backing off).
  uint8_t error() const { return error_; }

 private:
  enum class Phase : uint8_t { Idle, NextAxis, Clear, Fast, Backoff, Slow };
  bool nextAxis();
  RoutineStatus fail();
  int32_t steps(int32_t um) const { return m_.toSteps(axis_, um); }
  uint32_t homeRate(int32_t divisor) const;

  Motion& m_;
  const Config& c_;
  Phase phase_ = Phase::Idle;
  bool issued_ = false;
  uint8_t todo_ = 0, homed_ = 0, axis_ = 0, error_ = 0;
};

}  // namespace mega
