// Over-temperature and sensor-fault decisions for the six TMP36 channels, with per-sensor limits and hysteresis.
#include "thermal_guard.h"

namespace nano {

uint8_t ThermalGuard::update(const uint16_t mv[uv::kSensorCount]) {
  for (uint8_t i = 0; i < uv::kSensorCount; i++) {
    uint8_t bit = static_cast<uint8_t>(1u << i);
    bool broken = mv[i] < limits_.minMv || mv[i] > limits_.maxMv;
    broken_ = broken ? (broken_ | bit) : (broken_ & ~bit);
    if (broken) continue;  // a broken sensor's value means nothing; it faults on its own
    int16_t t = tmp36DeciC(mv[i]);
    if (t >= limits_.limitDeciC[i]) hot_ |= bit;
    else if (t < limits_.limitDeciC[i] - limits_.hysteresisDeciC) hot_ &= static_cast<uint8_t>(~bit);
  }
  active_ = static_cast<uint8_t>((hot_ ? uv::fault::kOvertemp : 0) | (broken_ ? uv::fault::kSensor : 0));
  return active_;
}

}  // namespace nano
