// A job's thermal checks before an exposure, and a paced job's waits to cool (protocol/mega.md
// "Pacing"): before a stop or a pass near a soft limit, and before a paced continue of a job paused hot.
#include "error_codes.h"
#include "job_runner.h"

namespace mega {

uint8_t sensorAtSoftLimit(const PrintheadLink& head, const Config& config) {
  const int16_t* t = head.deciC();
  for (uint8_t i = 0; i < uv::kSensorCount; i++)
    if (t[i] * 100 >= config.milli(Key::ThermalLimit0 + i)) return static_cast<uint8_t>(i + 1);
  return 0;
}

bool headHot(const PrintheadLink& head, const Config& config) {
  return (head.activeFaults() & uv::fault::kOvertemp) || sensorAtSoftLimit(head, config);
}

uint8_t JobRunner::exposureBlocked() const {
  if (head_.activeFaults() & uv::fault::kSensor) return uv::kSensorFault;
  if (tooHot() || head_.activeFaults()) return uv::kOverTemperature;
  if (!head_.online()) return uv::kNanoTimeout;
  return 0;
}

bool JobRunner::paceWaits(bool cooling) const {
  const int16_t* t = head_.deciC();
  for (uint8_t i = 0; i < uv::kSensorCount; i++) {
    int32_t limit = config_.milli(Key::ThermalLimit0 + i) / 100;
    if (cooling ? t[i] > limit - kPaceUntilDeciC : t[i] >= limit - kPaceAtDeciC) return true;
  }
  return false;
}

void JobRunner::cool(uint32_t nowUs) {
  if (pauseWanted_) {
    phase_ = Phase::Load;  // the stop (if one is in hand) is still in hand: the pause comes before it
    return;
  }
  // Only heat is waited out: a silent Nano or a broken sensor does not clear by cooling.
  if (!head_.online()) return fail(uv::kNanoTimeout);
  if (head_.activeFaults() & uv::fault::kSensor) return fail(uv::kSensorFault);
  // Cool: every reading kPaceUntilDeciC under its limit, and the Nano's OVERTEMP flag clear (the
  // exposure's checks would fail the job while it stands).
  if (paceWaits(true) || (head_.activeFaults() & uv::fault::kOvertemp)) return;
  changed_ = true;
  if (phase_ == Phase::CoolFirst) return continueAfterPause();
  // A stop in hand waited after its move: due at once, the checks again, then the exposure. A
  // scan job waited between passes: the checks again, then the pass.
  phase_ = stopInHand_ ? Phase::Settle : Phase::Scan;
  settleUntil_ = nowUs;
}

}  // namespace mega
