// Background temperature sampling: the ADC interrupt oversamples A0..A5 round robin, so T never waits.
// One conversion takes 104 µs (ADC clock 125 kHz); a channel gets 16 samples after one discarded
// settling sample, so a full sweep of six sensors takes about 10.6 ms.
#include "adc_sampler.h"

#include <avr/interrupt.h>
#include <avr/io.h>

#include "pins.h"
#include "thermal_guard.h"

namespace nano {
namespace adc_sampler {
namespace {

volatile uint16_t sums_[uv::kSensorCount];
volatile uint8_t sweeps_ = 0;
uint8_t taken_ = 0;
uint8_t channel_ = 0;
uint8_t samples_ = 0;
uint16_t acc_ = 0;
bool settle_ = true;

inline void select(uint8_t ch) { ADMUX = static_cast<uint8_t>(_BV(REFS0) | (TEMP_FIRST_CHANNEL + ch)); }

}  // namespace

void begin() {
  select(0);
  DIDR0 = 0x3F;  // digital input buffers off on A0..A5
  ADCSRA = _BV(ADEN) | _BV(ADIE) | _BV(ADPS2) | _BV(ADPS1) | _BV(ADPS0) | _BV(ADSC);
}

bool take(uint16_t mv[uv::kSensorCount]) {
  uint16_t sums[uv::kSensorCount];
  uint8_t sreg = SREG;
  cli();
  uint8_t sweeps = sweeps_;
  for (uint8_t i = 0; i < uv::kSensorCount; i++) sums[i] = sums_[i];
  SREG = sreg;
  if (sweeps == taken_) return false;
  taken_ = sweeps;
  for (uint8_t i = 0; i < uv::kSensorCount; i++) mv[i] = adcSumToMv(sums[i], kOversample);
  return true;
}

}  // namespace adc_sampler
}  // namespace nano

ISR(ADC_vect) {
  using namespace nano::adc_sampler;
  uint16_t v = ADC;
  if (settle_) {
    settle_ = false;  // the first conversion after a channel change is discarded
  } else {
    acc_ += v;
    if (++samples_ == kOversample) {
      sums_[channel_] = acc_;
      acc_ = 0;
      samples_ = 0;
      if (++channel_ == uv::kSensorCount) {
        channel_ = 0;
        sweeps_++;
      }
      select(channel_);
      settle_ = true;
    }
  }
  ADCSRA |= _BV(ADSC);
}
