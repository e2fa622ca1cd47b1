// Where a scan pass's stroke starts and ends in steps, its exact step interval, the step its G goes
// out with, and how much later than the Nano's time 0 the plan's start mark falls (issue 19).
//
// The head crosses one cell pitch p in the window W µs, so a step takes 2W·10⁶ / (p·S) timer ticks
// (S: milli-steps per mm), exact to 1/65536 tick. The Nano's time 0 is kMarkLeadUs after the step
// that sends G. The stroke starts far enough back that the ramp ends, and the G step comes, before
// the mark; the mark falls `shiftUs` after time 0, which delays every event by that much.
#pragma once
#include <stdint.h>

#include "nano_codec.h"
#include "scan_program.h"

namespace mega {

// From the step that sends G to the Nano's time 0: the G and its newline at the link's speed, two
// byte-times at the Mega's U2X divisor (UBRR (F/4/baud − 1)/2: 5 × (UBRR + 1) µs a byte at 16 MHz,
// 85 at 115200, 40 at 250000), then the Nano's kProgramStartLeadUs (protocol/nano.md "G: start").
constexpr uint32_t markLeadUs(uint32_t baud) { return uv::kProgramStartLeadUs + 2 * uv::linkByteUs(baud); }
constexpr uint32_t kMarkLeadUs = markLeadUs(115200);
static_assert(kMarkLeadUs == 1170 && markLeadUs(250000) == 1080, "two byte-times and the Nano's lead");

struct StrokePlan {
  int32_t startSteps;   // X at rest before the stroke
  int32_t steps;        // signed: the stroke's length and direction
  uint16_t interval;    // the middle's ticks a step, and 1/65536 ticks more
  uint16_t frac;
  uint32_t markStep;    // 1-based: the step that sends G
  uint32_t shiftUs;     // the plan's time 0 is this long after the Nano's
  uint16_t leadUs;      // markLeadUs at the link's speed when the stroke was planned
};

struct StrokeInput {
  int32_t markX2Um;     // twice the bed X of the start mark (half a pitch before window 0's column)
  int32_t endX2Um;      // twice the bed X where the last window ends
  bool descending;      // towards −X
  uint32_t windowUs;
  uint32_t pitchUm;
  uint32_t stepsMilli;  // X steps per mm × 1000
  uint32_t rampSteps;   // the stroke's ramp at its interval (Motion::strokeRampSteps)
  uint32_t linkBaud = 115200;  // the printhead link's speed, which times the G (markLeadUs)
};

// The interval of a step at the pass's speed, as 16.16 ticks; false if outside what the step engine
// runs (kMaxStepRate, 16-bit intervals).
bool strokeInterval(uint32_t windowUs, uint32_t pitchUm, uint32_t stepsMilli, uint16_t& interval, uint16_t& frac);
// False when the speed is out of range, or when the stroke's middle would take 2³² ticks (0.5 µs)
// or more: Motion counts them in 32 bits (about 35 minutes).
bool planStroke(const StrokeInput& in, StrokePlan& out);

// A pass whose last event comes this late after its start mark is refused before any light (M29):
// its stroke's middle, lead and ramps included, would not fit planStroke's 32-bit count of ticks.
constexpr uint32_t kScanLongestPassUs = 2100000000;

// A stretch the pass flies (the planner's jump: its first blank window, its windows, its µs) in the
// stroke's steps, as Motion::StrokeJump takes it: it leaves the speed `from` steps into the stroke,
// the last step at or before the stretch's start, and is back at it `steps` later, the first step at
// or after its end, having saved 2 × (windows × W − µs) ticks.
void strokeJump(const StrokePlan& k, uint32_t windowUs, uint32_t window, uint32_t windows, uint32_t flyUs, uint32_t& from,
                uint32_t& steps, uint32_t& savedTicks);

}  // namespace mega
