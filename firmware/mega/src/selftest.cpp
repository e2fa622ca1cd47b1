// The kinematic self-test (M822): out, then back to each endstop counting steps.
#include "selftest.h"

#include <string.h>

#include "progmem.h"
#include "text_scan.h"

namespace mega {

int32_t SelfTest::reach(uint8_t axis) const {
  int32_t bed = c_.milli(axis ? Key::BedY : Key::BedX);
  return quick_ && kQuickTestUm < bed ? kQuickTestUm : bed;
}

void SelfTest::start(bool quick) {
  quick_ = quick;
  pass_[0] = pass_[1] = false;
  counted_[0] = counted_[1] = 0;
  int32_t to[3];
  m_.targetUm(to);
  to[0] = reach(0);
  to[1] = reach(1);
  phase_ = m_.moveTo(to, 0) ? Phase::Out : Phase::Idle;
}

void SelfTest::judge(uint8_t axis) {
  counted_[axis] = m_.engine().seekSteps();
  int32_t expected = m_.toSteps(axis, reach(axis));
  int32_t off = static_cast<int32_t>(counted_[axis]) - expected;
  if (off < 0) off = -off;
  pass_[axis] = m_.engine().seekHit() && off <= m_.toSteps(axis, kSelfTestToleranceUm);
  if (m_.engine().seekHit()) {
    int32_t pos[3];
    m_.positionSteps(pos);
    pos[axis] = 0;
    m_.setPositionSteps(pos);
  }
}

RoutineStatus SelfTest::poll() {
  if (phase_ == Phase::Idle) return RoutineStatus::Idle;
  if (!m_.idle()) return RoutineStatus::Running;
  uint32_t rate;
  switch (phase_) {
    case Phase::Out:
      rate = m_.rateFor(0, c_.milli(Key::SpeedHome));
      if (!m_.seek(0, -m_.toSteps(0, reach(0) + kHomeBackoffUm), rate)) return RoutineStatus::Running;
      phase_ = Phase::SeekX;
      return RoutineStatus::Running;
    case Phase::SeekX:
      judge(0);
      rate = m_.rateFor(1, c_.milli(Key::SpeedHome));
      if (!m_.seek(1, -m_.toSteps(1, reach(1) + kHomeBackoffUm), rate)) return RoutineStatus::Running;
      phase_ = Phase::SeekY;
      return RoutineStatus::Running;
    case Phase::SeekY:
      judge(1);
      phase_ = Phase::Idle;
      return RoutineStatus::Done;
    default:
      return RoutineStatus::Idle;
  }
}

uint8_t SelfTest::format(char* out) const {
  char* p = out;
  p += uv::putFlash(quick_ ? UV_P("TEST:quick") : UV_P("TEST:full"), p);
  for (uint8_t a = 0; a < 2; a++) {
    p += uv::putFlash(a ? UV_P(" y=") : UV_P(" x="), p);
    p += uv::putFlash(pass_[a] ? UV_P("pass") : UV_P("fail"), p);
    p += uv::putFlash(a ? UV_P(" y_steps=") : UV_P(" x_steps="), p);
    p += uv::putUnsigned(counted_[a], p);
  }
  *p = 0;
  return static_cast<uint8_t>(p - out);
}

}  // namespace mega
