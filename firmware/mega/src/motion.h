// The main loop's side of motion: moves in µm become step blocks with trapezoidal profiles, fed to
// the step interrupt as segments; controlled and immediate stops; endstop seeks for homing.
#pragma once
#include <stdint.h>

#include "config.h"
#include "jump_path.h"
#include "step_engine.h"
#include "step_profile.h"

namespace mega {

// Starts the step interrupt if it stopped and work is queued (hw/stepper_timer.cpp on the board;
// nothing on the host, whose rig starts it). Motion calls it as soon as a plain move's first segment is in.
void stepperKick();

class Motion {
 public:
  Motion(StepEngine& engine, const Config& config) : e_(engine), c_(config) {}

  // Queues a move to `um` (bed µm) at up to `feedUmS` per axis (0: the configured speeds).
  // False when the queue is full or a stop is still running down: try again later.
  bool moveTo(const int32_t um[3], uint32_t feedUmS);
  // The same to a position in steps (a scan pass's start, which must be exact).
  bool moveToSteps(const int32_t steps[3]);
  // Queues a move of `steps` on one axis towards −/+ that ends early when the axis's endstop closes.
  bool seek(uint8_t axis, int32_t steps, uint32_t rateStepsS);
  // Queues a move of `steps` on one axis at a given rate (homing back-off).
  bool moveSteps(uint8_t axis, int32_t steps, uint32_t rateStepsS);
  // A scan pass's stroke (issue 19): an X move of `steps` from rest to rest whose middle, all but
  // the ramps at either end, runs at exactly `interval` + frac/65536 ticks a step, the fraction
  // carried from step to step. Step `markStep` (1-based, in that middle; 0 for none) goes out with
  // the pass's G (StepTick::mark). The ramps are the X axis's acceleration. One stroke at a time.
  // `jumps`, if set, gives the stroke's flown stretches in order (jump i, false past the last),
  // asked for as the middle is cut into segments.
  struct StrokeJump {
    uint32_t from;        // steps into the stroke where the stretch begins (at the speed)
    uint32_t steps;       // it ends `steps` later, back at the speed,
    uint32_t savedTicks;  // this much sooner than at the speed (jump_path.h)
  };
  typedef bool (*JumpSource)(void* ctx, uint8_t i, StrokeJump& out);
  struct Stroke {
    int32_t steps;
    uint16_t interval, frac;
    uint32_t markStep;
    JumpSource jumps;
    void* ctx;
  };
  bool stroke(const Stroke& s);
  // A Y hop of `dy` steps that glides (glide.h, planner.md "Gliding"): at once, on its own timing,
  // beside whatever X does (a stroke's run-out, the X move queued after it) or at rest. False when
  // nothing may glide now (a queued move or a glide moves Y, or a stop runs down) or the hop cannot
  // glide at all (glides()). While it runs, a move that would move Y waits (false: try again).
  bool glide(int32_t dy);
  bool glides(int32_t dy) const;
  // Steps the stroke's ramp takes at either end (the middle begins after them).
  uint32_t strokeRampSteps(uint16_t interval, uint16_t frac) const;
  // Feeds the step interrupt; call every pass of the main loop. Never waits.
  void poll();
  // Decelerates to rest at the configured acceleration and drops every queued move (M410, jog end).
  void stop();
  // Stops at once (M112, a fault). The position may be off afterwards: the axes count as unhomed.
  void halt();

  bool idle() const { return !stopping_ && planSlot_ < 0 && e_.idle(); }
  // A stroke is queued whose segments are not all cut yet (its jumps are still asked for).
  bool cuttingStroke() const { return strokeSlot_ >= 0; }
  bool accepting() const { return !stopping_ && e_.blocksFree() > 0; }
  uint8_t movesFree() const { return stopping_ ? 0 : e_.blocksFree(); }
  void positionSteps(int32_t out[3]) const { e_.position(out); }
  void positionUm(int32_t out[3]) const;
  // Declares the current position (after homing).
  void setPositionSteps(const int32_t steps[3]);
  // Where the queued moves end, µm (the base of a relative move).
  void targetUm(int32_t out[3]) const;
  void targetSteps(int32_t out[3]) const {
    for (uint8_t a = 0; a < 3; a++) out[a] = target_[a];
  }

  const StepEngine& engine() const { return e_; }
  int32_t toSteps(uint8_t axis, int32_t um) const;
  uint32_t stepsMilli(uint8_t axis) const;  // steps per mm × 1000
  int32_t toUm(uint8_t axis, int32_t steps) const;
  // Whether `steps` on X or Y lies on the bed, 0 to its size (bed.x, bed.y), as G0's soft limits say.
  bool onBed(uint8_t axis, int32_t steps) const;
  // Steps/s for a speed in thousandths of mm/s on an axis.
  uint32_t rateFor(uint8_t axis, int32_t milliMmS) const;
  AxisLimits limits(uint8_t axis, uint32_t feedUmS) const;

 private:
  bool push(const int32_t delta[3], const AxisLimits lim[3], int8_t seekAxis);
  // Cuts segments until the queue is full. `kickFirst`: starts the interrupt after the first (not
  // for a stroke, whose short ramp and flown segments take longer to cut).
  void feed(bool kickFirst = false);
  Profile strokeProfile(uint32_t steps, uint16_t interval, uint16_t frac) const;
  // A segment of the stroke's middle from planDone_: at the speed (at most `most` steps) up to the
  // next stretch flown, or the flown stretch's next piece.
  void strokeSegment(uint16_t most, uint16_t& steps, uint16_t& interval, uint16_t& frac);
  void nextJump();
  // A stop or a halt: no stroke is cut any more, nor its stretches flown.
  void forgetStroke();

  StepEngine& e_;
  const Config& c_;
  Profile profiles_[StepEngine::kBlocks];
  int32_t target_[3] = {};  // steps, where the queued moves end
  int8_t planSlot_ = -1;    // the block being cut into segments
  uint8_t nextPlan_ = 0;    // sequence number of the next block to cut
  uint32_t planDone_ = 0;
  bool stopping_ = false;
  // The stroke queued or running: its block's slot (−1: none), exact interval and mark.
  int8_t strokeSlot_ = -1;
  uint16_t strokeInterval_ = 0, strokeFrac_ = 0;
  uint32_t strokeMark_ = 0;
  // The middle's timing: ticks its queued steps take (as the step interrupt carries the fraction,
  // mirrored in fracAcc_), and what the flown stretches queued so far saved.
  uint32_t midTicks_ = 0, savedTicks_ = 0;
  uint16_t fracAcc_ = 0;
  // The stroke's next flown stretch (held) and whether its segments are being cut (flying).
  JumpSource jumps_ = nullptr;
  void* jumpCtx_ = nullptr;
  uint8_t jumpNext_ = 0;
  bool jumpHeld_ = false, flying_ = false;
  StrokeJump jump_ = {};
  JumpPath path_;
};

}  // namespace mega
