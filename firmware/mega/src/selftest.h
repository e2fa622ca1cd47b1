// The kinematic self-test (M822): drive X and Y out, then seek each back to its endstop counting
// steps. A count that differs from the distance by more than kSelfTestToleranceUm means lost steps,
// a slipping belt or a loose switch. The seek re-homes the axis.
#pragma once
#include <stdint.h>

#include "homing.h"

namespace mega {

constexpr int32_t kQuickTestUm = 20000;      // the quick test's travel, if the bed is that long
constexpr int32_t kSelfTestToleranceUm = 100;

class SelfTest {
 public:
  SelfTest(Motion& motion, const Config& config) : m_(motion), c_(config) {}

  // X and Y must be homed.
  void start(bool quick);
  RoutineStatus poll();
  bool quick() const { return quick_; }
  bool pass(uint8_t axis) const { return pass_[axis]; }
  uint32_t counted(uint8_t axis) const { return counted_[axis]; }
  bool allPass() const { return pass_[0] && pass_[1]; }
  // The `TEST:` report line (protocol/mega.md §4) and a NUL; returns its length.
  uint8_t format(char* out) const;

 private:
  enum class Phase : uint8_t { Idle, Out, SeekX, SeekY };
  int32_t reach(uint8_t axis) const;
  void judge(uint8_t axis);

  Motion& m_;
  const Config& c_;
  Phase phase_ = Phase::Idle;
  bool quick_ = false;
  bool pass_[2] = {};
  uint32_t counted_[2] = {};
};

}  // namespace mega
