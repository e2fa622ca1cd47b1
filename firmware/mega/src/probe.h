// One probe of the bed (G30, and each point of G29): lower Z slowly until the CR Touch triggers,
// read through the Nano's latched P, stop, note the Z, and lift again. A probe that is in alarm
// or never triggers is recovered (alarm release, deploy again) and tried twice more.
#pragma once
#include <stdint.h>

#include "homing.h"
#include "motion.h"
#include "printhead_link.h"

namespace mega {

constexpr int32_t kProbeSpeedUmS = 3000;   // 3 mm/s: a millisecond of P-poll latency is 3 µm
constexpr int32_t kProbeFloorUm = -3000;   // how far below Z 0 a probe may reach for the bed
constexpr int32_t kProbeLiftUm = 5000;     // above the point found, before moving on
constexpr uint8_t kProbeTries = 3;
constexpr uint32_t kServoSettleUs = 300000;  // the CR Touch's pin needs this long to move

class Probe {
 public:
  Probe(Motion& motion, PrintheadLink& head) : m_(motion), head_(head) {}

  void start(uint32_t nowUs);
  RoutineStatus poll(uint32_t nowUs);
  void cancel() { phase_ = Phase::Idle; }
  // The bed's Z where the probe triggered, µm; and the X, Y it was at.
  int32_t zUm() const { return z_; }
  // 40 (alarm) or 41 (no trigger) after the last try failed; 30 if the Nano went silent.
  uint8_t error() const { return error_; }

 private:
  enum class Phase : uint8_t { Idle, Check, Descend, Stopping, Lift, Release, Deploy, Settle };
  RoutineStatus retry(uint8_t code, uint32_t nowUs);

  Motion& m_;
  PrintheadLink& head_;
  Phase phase_ = Phase::Idle;
  Phase after_ = Phase::Idle;
  uint32_t until_ = 0;
  int32_t z_ = 0;
  uint8_t tries_ = 0, error_ = 0;
};

}  // namespace mega
