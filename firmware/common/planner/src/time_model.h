// Move times (the continuous trapezoid, and the Mega's step engine as it runs a move) and the
// per-stop clock of protocol/planner.md "Time model", in integer µs.
#pragma once
#include <stdint.h>

#include "isqrt.h"
#include "job_types.h"
#include "nano_codec.h"

namespace uv {

struct MotionModel {
  uint32_t vmaxUmS[2];
  uint32_t accelUmS2[2];
  uint32_t settleUs;
  uint32_t overheadUs;
  int32_t startUm[2];
  uint32_t stepsMilli[2];  // X and Y steps per mm × 1000: the step engine moves in whole steps
  // The printhead link's speed the job runs at (one of nanoLinkBaud's; planner.md "Time model", "The
  // printhead link"): it times each stop's F line, a pass's G lead and its programs on the wire.
  uint32_t linkBaud = kNanoBaud;
};

// The Mega's step engine as the time model prices it (firmware/mega/src/step_profile.h, whose
// numbers these are; motion_test checks the two agree): a 2 MHz step timer, 32 to 16000 steps/s on
// the dominant axis, segments of about 2.5 ms (400 a second) at the rate at their middle.
constexpr uint32_t kEngineTickHz = 2000000;
constexpr uint32_t kEngineMaxRate = 16000;
constexpr uint32_t kEngineMinRate = 32;
constexpr uint32_t kEngineSegmentsPerS = 400;

// A move's profile on its dominant axis, in steps (step_profile.h's Profile).
struct StepRamp {
  uint32_t total, rate, accel, ramp;
};
// From X's and Y's steps and limits (steps/s, steps/s²), as profileFor() scales them to the dominant
// axis. (Scalars: on the AVR a constant array would be copied into RAM.)
StepRamp stepRamp(uint32_t stepsX, uint32_t rateX, uint32_t accelX, uint32_t stepsY, uint32_t rateY, uint32_t accelY);
// Timer ticks (0.5 µs) the engine takes for steps [from, to) of a move, segment by segment as
// Motion cuts them (a segment that would run past `to` ends there at the rate it was given),
// each step's interval counted, the last one's too (the engine is idle only after it).
uint64_t stepTicks(const StepRamp& p, uint32_t from, uint32_t to);
// An axis's position in steps for `um` (Motion::toSteps: rounded half away from zero).
int32_t axisSteps(const MotionModel& m, uint8_t axis, int32_t um);
// The axis's top rate (steps/s) and acceleration (steps/s²), as Motion::limits gives them.
uint32_t axisRate(const MotionModel& m, uint8_t axis);
uint32_t axisAccel(const MotionModel& m, uint8_t axis);
// The µs the step engine takes to move by (dx, dy) steps from rest to rest, until it is idle.
uint32_t engineMoveUs(const MotionModel& m, uint32_t dx, uint32_t dy);
// The same between two bed positions (µm).
uint32_t engineMoveUs(const MotionModel& m, int32_t fromX, int32_t fromY, int32_t toX, int32_t toY);

struct Stop {
  int32_t hx, hy;   // head position in cells
  uint32_t us[4];   // per LED
};

uint64_t isqrt64(uint64_t n);
// Time in µs to move d µm on one axis, from rest to rest, on the continuous trapezoid (a scan
// pass's flown stretch is planned on it: the Mega flies it in exactly that time).
uint32_t moveTimeUs(uint32_t d, uint32_t v, uint32_t a);

// µs the stop's F:m,d0,d1,d2,d3 line takes on the printhead link at `baud`, ten bits a byte,
// rounded down (planner.md "Time model"); 0 for a stop that lights nothing (no F goes).
uint32_t fireLineUs(const uint32_t us[4], uint32_t baud);
// One stop's time from the previous head position (bed µm): the step engine's move, settle if
// it moved, the per-stop overhead, its F line on the wire and its longest LED duration.
uint32_t stopCostUs(const MotionModel& m, int32_t fromX, int32_t fromY, int32_t toX, int32_t toY, const uint32_t us[4]);
// The same after a move of (dx, dy) steps: the one rule every planner prices a stop by.
uint32_t stopCostStepsUs(const MotionModel& m, int32_t dx, int32_t dy, const uint32_t us[4]);

// Adds up the estimate stop by stop, as the planner emits them.
class PlanClock {
 public:
  PlanClock(const JobHeader& h, const MotionModel& m) : h_(h), m_(m), x_(m.startUm[0]), y_(m.startUm[1]) {}
  void add(const Stop& s);
  uint64_t totalUs() const { return total_; }
  uint64_t travelUm(uint8_t axis) const { return travel_[axis]; }

 private:
  const JobHeader& h_;
  const MotionModel& m_;
  int32_t x_, y_;
  uint64_t total_ = 0;
  uint64_t travel_[2] = {0, 0};
};

}  // namespace uv
