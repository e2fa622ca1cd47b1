// Rest-to-rest trapezoidal motion in steps: each move's profile on its step-dominant axis, and the
// short constant-rate segments the step interrupt runs (the main loop computes them, so the
// interrupt never divides or takes a square root).
#pragma once
#include <stdint.h>

namespace mega {

constexpr uint32_t kTickHz = 2000000;     // step timer: 16 MHz / 8
// Steps/s on the dominant axis: a 62.5 µs period, over the step interrupt's longest 39 µs measured
// in simavr (board_sim_test), so it never falls behind (200 mm/s at 80 steps/mm).
constexpr uint32_t kMaxStepRate = 16000;
constexpr uint32_t kMinStepRate = 32;     // keeps an interval within 16 bits
constexpr uint32_t kSegmentUs = 2500;     // a segment's length in time, at its rate

// One axis's limits, in steps: rate (steps/s) and acceleration (steps/s²).
struct AxisLimits {
  uint32_t rate;
  uint32_t accel;
};

// The dominant axis's profile. Every other axis steps in proportion (Bresenham), so it keeps
// within its own limits when the dominant one keeps within these.
struct Profile {
  uint32_t total;      // steps of the dominant axis
  uint32_t rate;       // cruise rate, steps/s
  uint32_t accel;      // steps/s²
  uint32_t rampSteps;  // steps from rest to `rate`: rate² / (2 accel), rounded up
};

Profile profileFor(const uint32_t steps[3], const AxisLimits limits[3]);

struct Segment {
  uint16_t steps;
  uint16_t interval;  // timer ticks between steps
};

// The segment that starts `done` steps into the move: its rate is the profile's at the
// segment's middle, from rest at either end.
Segment nextSegment(const Profile& p, uint32_t done);

// The rate at twice-distance d2 (in half steps) from the nearer end of the move.
uint32_t rateAt(const Profile& p, uint32_t d2);

// Steps needed to come to rest from `rate`, rounded up.
uint32_t stoppingSteps(const Profile& p, uint32_t rate);

}  // namespace mega
