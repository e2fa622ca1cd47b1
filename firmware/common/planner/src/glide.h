// The Y hop between two scan passes as the step interrupt runs it beside X's run-out (protocol/
// planner.md "Gliding"): a few Y steps from rest to rest, speeding up at the axis's acceleration for
// the first half and slowing down over the second, on a timing of their own while X ramps down.
//
// Each interval comes from the one before by the recurrence of D. Austin's "Generate stepper-motor
// speed profiles in real time" (Atmel AVR446): c_i = c_(i−1) × (4i − 1) / (4i + 1), one 16-bit
// division a step and no square root, so the interrupt can work it out. Its only large error is its
// first step (0.6 where constant acceleration gives √2 − 1), which AVR446 offsets by shortening c_0
// by 0.676, speeding the first step up twice as hard as the axis allows. Here c_0 is the exact
// √(2/a) and c_1 is c_0 × (√2 − 1) rounded up, so no step speeds up harder than `accel` (glide_test);
// the way down is the inverse, rounded down, so no step slows down harder either. The Mega's engine
// and the planner both time a glide with these functions: the planner's price is the engine's time.
#pragma once
#include <stdint.h>

namespace uv {

// A glide of at most this many steps (its counters are bytes).
constexpr uint8_t kGlideMaxSteps = 255;
// Its first interval fits 15 bits, so twice any interval fits 16 (the division's numerator): an
// acceleration of at least 7451 steps/s² (93 mm/s² at 80 steps/mm) glides.
constexpr uint16_t kGlideMaxInterval = 32767;

struct Glide {
  uint16_t interval;  // ticks (0.5 µs) to the next step
  uint8_t left;       // steps to go
  uint8_t steps;      // in all
};

// The interval after the one in `g`, once a step is taken and `left` counted down (left ≥ 1).
// p = steps − left intervals have gone, j = left − 1 remain after this one: up while p ≤ j (the
// middle of an odd count too), level at the turn of an even count, then down, mirroring the way up.
inline uint16_t glideNext(const Glide& g) {
  const uint16_t c = g.interval, twice = static_cast<uint16_t>(2 * c);
  const uint16_t n = g.steps, left = g.left;
  if (n + 1 <= 2 * left) {
    if (n - left == 1) return static_cast<uint16_t>((static_cast<uint32_t>(c) * 27146u + 65535u) >> 16);  // × (√2 − 1), up
    return static_cast<uint16_t>(c - twice / static_cast<uint16_t>(4 * (n - left) + 1));
  }
  if (n == 2 * left) return c;
  if (left == 1) return static_cast<uint16_t>((static_cast<uint32_t>(c) * 158217u) >> 16);  // × (√2 + 1), down
  return static_cast<uint16_t>(c + twice / static_cast<uint16_t>(4 * left - 1));
}

// A glide of `steps` at an axis's top rate and acceleration (steps/s, steps/s²), as Motion::limits
// gives them: its first interval, its ticks from its start to its last step, and whether it can
// glide (1 to kGlideMaxSteps steps, a first interval within kGlideMaxInterval, and no interval
// shorter than the rate allows or than 125 ticks, the engine's 16000 steps/s).
struct GlidePlan {
  uint16_t first;
  uint32_t ticks;
};
bool planGlide(uint32_t steps, uint32_t rate, uint32_t accel, GlidePlan& out);

}  // namespace uv
