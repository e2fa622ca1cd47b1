// Over-temperature and sensor-fault decisions for the six TMP36 channels, with per-sensor limits and hysteresis.
#pragma once
#include <stdint.h>

#include "nano_codec.h"

namespace nano {

struct ThermalLimits {
  int16_t limitDeciC[uv::kSensorCount];
  int16_t hysteresisDeciC;
  uint16_t minMv;  // below: open or shorted to ground
  uint16_t maxMv;  // above: shorted to the supply
};

// TMP36: 10 mV/°C with 500 mV at 0 °C, so tenths of a degree = mV - 500.
inline int16_t tmp36DeciC(uint16_t mv) { return static_cast<int16_t>(static_cast<int32_t>(mv) - 500); }

// Oversampled ADC sum (n samples of 10 bits against AVcc = 5000 mV) to mV, rounded.
inline uint16_t adcSumToMv(uint32_t sum, uint8_t n) {
  return static_cast<uint16_t>((sum * 5000u + 512u * n) / (1024u * n));
}

class ThermalGuard {
 public:
  explicit ThermalGuard(const ThermalLimits& limits) : limits_(limits) {}

  // Takes a fresh reading of all sensors; returns the active fault bits (uv::fault::kOvertemp, kSensor).
  uint8_t update(const uint16_t mv[uv::kSensorCount]);

  uint8_t active() const { return active_; }
  uint8_t hotMask() const { return hot_; }
  uint8_t brokenMask() const { return broken_; }

 private:
  const ThermalLimits& limits_;
  uint8_t hot_ = 0;     // per sensor: over limit, not yet cooled below limit - hysteresis
  uint8_t broken_ = 0;  // per sensor: open or shorted
  uint8_t active_ = 0;
};

}  // namespace nano
