// Background temperature sampling: the ADC interrupt oversamples A0..A5 round robin, so T never waits.
#pragma once
#include <stdint.h>

#include "nano_codec.h"

namespace nano {
namespace adc_sampler {

constexpr uint8_t kOversample = 16;

void begin();
// Copies the latest full sweep in mV; true when a sweep finished since the last call.
bool take(uint16_t mv[uv::kSensorCount]);

}  // namespace adc_sampler
}  // namespace nano
