// Homing on the endstops (G28): per axis, Z first, a fast seek, an exact back-off, and a slow seek
// whose closing point becomes 0.
#include "homing.h"

#include "error_codes.h"

namespace mega {

namespace {
const Key kBed[3] = {Key::BedX, Key::BedY, Key::BedZ};
const uint8_t kOrder[3] = {2, 0, 1};
}  // namespace

void Homing::start(uint8_t axes) {
  todo_ = axes & 7;
  homed_ = 0;
  error_ = 0;
  phase_ = Phase::NextAxis;
  issued_ = false;
}

uint32_t Homing::homeRate(int32_t divisor) const {
  int32_t speed = c_.milli(Key::SpeedHome) / divisor;
  if (axis_ == 2 && speed > c_.milli(Key::SpeedZ)) speed = c_.milli(Key::SpeedZ);
  uint32_t r = m_.rateFor(axis_, speed);
  return r < kMinStepRate ? kMinStepRate : r;
}

bool Homing::nextAxis() {
  for (uint8_t a : kOrder) {
    if (todo_ & (1 << a)) {
      todo_ = static_cast<uint8_t>(todo_ & ~(1 << a));
      axis_ = a;
      return true;
    }
  }
  return false;
}

RoutineStatus Homing::fail() {
  phase_ = Phase::Idle;
  error_ = uv::kHomingFailed;
  return RoutineStatus::Failed;
}

RoutineStatus Homing::poll(uint8_t endstops) {
  if (phase_ == Phase::Idle) return error_ ? RoutineStatus::Failed : RoutineStatus::Idle;
  if (!m_.idle()) return RoutineStatus::Running;
  bool closed = endstops & (1 << axis_);
  if (issued_) {  // the phase's motion has finished: judge it
    issued_ = false;
    switch (phase_) {
      case Phase::Clear:
        if (closed) return fail();  // stuck closed
        phase_ = Phase::Fast;
        break;
      case Phase::Fast:
        if (!m_.engine().seekHit()) return fail();  // no switch over the whole travel
        phase_ = Phase::Backoff;
        break;
      case Phase::Backoff:
        if (closed) return fail();
        phase_ = Phase::Slow;
        break;
      case Phase::Slow: {
        if (!m_.engine().seekHit()) return fail();
        int32_t pos[3];
        m_.positionSteps(pos);
        pos[axis_] = 0;  // exactly where the switch closed
        m_.setPositionSteps(pos);
        homed_ = static_cast<uint8_t>(homed_ | (1 << axis_));
        phase_ = Phase::NextAxis;
        break;
      }
      default:
        break;
    }
  }
  if (phase_ == Phase::NextAxis) {
    if (!nextAxis()) {
      phase_ = Phase::Idle;
      return RoutineStatus::Done;
    }
    phase_ = (endstops & (1 << axis_)) ? Phase::Clear : Phase::Fast;  // already on the switch: off it first
  }
  bool ok = false;
  switch (phase_) {
    case Phase::Clear:
    case Phase::Backoff:
      ok = m_.moveSteps(axis_, steps(kHomeBackoffUm), homeRate(1));
      break;
    case Phase::Fast:
      ok = m_.seek(axis_, -steps(c_.milli(kBed[axis_]) + 10000), homeRate(1));  // the bed and 10 mm
      break;
    case Phase::Slow:
      ok = m_.seek(axis_, -2 * steps(kHomeBackoffUm), homeRate(kHomeSlowDivisor));
      break;
    default:
      break;
  }
  issued_ = ok;
  return RoutineStatus::Running;
}

}  // namespace mega
