// One probe of the bed: down until the CR Touch triggers, note Z, lift; recover and retry on alarm.
#include "probe.h"

#include "error_codes.h"

namespace mega {

namespace {
bool due(uint32_t now, uint32_t at) { return static_cast<int32_t>(now - at) >= 0; }
}  // namespace

void Probe::start(uint32_t) {
  tries_ = 0;
  error_ = 0;
  phase_ = Phase::Check;
  head_.requestProbe();
}

RoutineStatus Probe::retry(uint8_t code, uint32_t nowUs) {
  if (++tries_ >= kProbeTries) {
    error_ = code;
    phase_ = Phase::Idle;
    return RoutineStatus::Failed;
  }
  // Alarm release, then deploy again, each with the servo's time to move.
  head_.servo('X');
  phase_ = Phase::Settle;
  after_ = Phase::Release;
  until_ = nowUs + kServoSettleUs;
  return RoutineStatus::Running;
}

RoutineStatus Probe::poll(uint32_t nowUs) {
  if (phase_ == Phase::Idle) return error_ ? RoutineStatus::Failed : RoutineStatus::Idle;
  if (!head_.online()) {
    m_.stop();
    error_ = uv::kNanoTimeout;
    phase_ = Phase::Idle;
    return RoutineStatus::Failed;
  }
  switch (phase_) {
    case Phase::Check:
      // Triggered before moving: the pin is not out (the CR Touch's alarm) or already on the bed.
      if (!head_.probeAnswered()) return RoutineStatus::Running;
      if (head_.probeTriggered()) return retry(uv::kProbeAlarm, nowUs);
      {
        int32_t to[3];
        m_.targetUm(to);
        to[2] = kProbeFloorUm;
        if (!m_.moveTo(to, kProbeSpeedUmS)) return RoutineStatus::Running;
      }
      head_.requestProbe();
      phase_ = Phase::Descend;
      return RoutineStatus::Running;
    case Phase::Descend: {
      if (head_.probeAnswered()) {
        if (head_.probeTriggered()) {
          int32_t at[3];
          m_.positionUm(at);
          z_ = at[2];  // where Z was when the latched trigger was read: within a poll of it
          m_.stop();
          phase_ = Phase::Stopping;
          return RoutineStatus::Running;
        }
        head_.requestProbe();  // keep asking while Z goes down
      }
      if (m_.idle()) return retry(uv::kProbeNoTrigger, nowUs);  // reached the floor untouched
      return RoutineStatus::Running;
    }
    case Phase::Stopping: {
      if (!m_.idle()) return RoutineStatus::Running;
      int32_t to[3];
      m_.targetUm(to);
      to[2] = z_ + kProbeLiftUm;
      if (!m_.moveTo(to, 0)) return RoutineStatus::Running;
      phase_ = Phase::Lift;
      return RoutineStatus::Running;
    }
    case Phase::Lift:
      if (!m_.idle()) return RoutineStatus::Running;
      phase_ = Phase::Idle;
      return RoutineStatus::Done;
    case Phase::Settle:
      if (!due(nowUs, until_)) return RoutineStatus::Running;
      phase_ = after_;
      return RoutineStatus::Running;
    case Phase::Release:
      head_.servo('D');
      phase_ = Phase::Settle;
      after_ = Phase::Deploy;
      until_ = nowUs + kServoSettleUs;
      return RoutineStatus::Running;
    case Phase::Deploy:
      head_.requestProbe();
      phase_ = Phase::Check;
      return RoutineStatus::Running;
    default:
      return RoutineStatus::Running;
  }
}

}  // namespace mega
