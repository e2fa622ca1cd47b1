// Move times (the continuous trapezoid, and the Mega's step engine) and the per-stop clock of
// protocol/planner.md "Time model", in integer µs.
#include "time_model.h"

namespace uv {

namespace {
uint64_t roundDiv(uint64_t n, uint64_t d) {
  uint64_t q = n / d;
  return (n - q * d) * 2 >= d ? q + 1 : q;
}
uint32_t absDiff(int32_t a, int32_t b) { return static_cast<uint32_t>(a > b ? a - b : b - a); }
}  // namespace

uint64_t isqrt64(uint64_t n) {
  if (n < 2) return n;
  // Newton's method from above, from the power of two at or above the root: a handful of 64-bit
  // divisions rather than one for every bit of n (each is about 0.2 ms on the Mega).
  uint8_t bits = 0;
  for (uint64_t m = n; m; m >>= 1) bits++;
  uint64_t x = 1ull << ((bits + 1) / 2), y = (x + n / x) / 2;
  while (y < x) {
    x = y;
    y = (x + n / x) / 2;
  }
  return x;
}

namespace {
// One moving axis's limits, scaled up to the dominant axis's `total` steps.
void scaleLimits(StepRamp& p, uint32_t steps, uint32_t rate, uint32_t accel) {
  if (!steps) return;
  const uint64_t r = static_cast<uint64_t>(rate) * p.total / steps;
  const uint64_t c = static_cast<uint64_t>(accel) * p.total / steps;
  if (r < p.rate) p.rate = static_cast<uint32_t>(r);
  if (c < p.accel) p.accel = static_cast<uint32_t>(c);
}
}  // namespace

StepRamp stepRamp(uint32_t stepsX, uint32_t rateX, uint32_t accelX, uint32_t stepsY, uint32_t rateY, uint32_t accelY) {
  StepRamp p{stepsX > stepsY ? stepsX : stepsY, kEngineMaxRate, 0xffffffffu, 0};
  scaleLimits(p, stepsX, rateX, accelX);
  scaleLimits(p, stepsY, rateY, accelY);
  if (p.rate < kEngineMinRate) p.rate = kEngineMinRate;
  if (p.accel < 1) p.accel = 1;
  const uint64_t twoA = 2ull * p.accel;
  p.ramp = static_cast<uint32_t>((static_cast<uint64_t>(p.rate) * p.rate + twoA - 1) / twoA);
  return p;
}

namespace {
// The rate at twice-distance d2 (half steps) from the nearer end (step_profile.cpp's rateAt).
uint32_t rateAt(const StepRamp& p, uint32_t d2) {
  if (d2 >= 2 * p.ramp) return p.rate;
  uint32_t r = isqrt32(p.accel * d2);
  if (r > p.rate) r = p.rate;
  return r < kEngineMinRate ? kEngineMinRate : r;
}
uint32_t segmentSteps(uint32_t rate, uint32_t remaining) {
  uint32_t k = rate / kEngineSegmentsPerS;
  if (k < 1) k = 1;
  if (k > remaining) k = remaining;
  return k > 0xffff ? 0xffff : k;
}
}  // namespace

uint64_t stepTicks(const StepRamp& p, uint32_t from, uint32_t to) {
  uint64_t ticks = 0;
  for (uint32_t done = from; done < to;) {
    const uint32_t remaining = p.total - done;
    if (done >= p.ramp) {
      // At the cruise rate: whole segments that stay clear of the ramp down, counted at once.
      const uint32_t k = segmentSteps(p.rate, 0xffffffffu);
      const uint64_t need = 2ull * p.ramp + k > 2ull * k ? 2ull * p.ramp + k : 2ull * k;
      if (2ull * remaining >= need) {
        uint64_t n = (2ull * remaining - need) / (2ull * k) + 1;
        if (n > (to - done) / k) n = (to - done) / k;
        if (n) {
          ticks += n * k * (kEngineTickHz / p.rate);
          done += static_cast<uint32_t>(n * k);
          continue;
        }
      }
    }
    const uint32_t fromStart = 2 * done + 1, fromEnd = 2 * remaining - 1;
    uint32_t k = segmentSteps(rateAt(p, fromStart < fromEnd ? fromStart : fromEnd), remaining);
    const uint32_t midStart = 2 * done + k, midEnd = 2 * remaining - k;
    const uint32_t interval = kEngineTickHz / rateAt(p, midStart < midEnd ? midStart : midEnd);
    if (k > to - done) k = to - done;
    ticks += static_cast<uint64_t>(k) * interval;
    done += k;
  }
  return ticks;
}

int32_t axisSteps(const MotionModel& m, uint8_t axis, int32_t um) {
  const int64_t n = static_cast<int64_t>(um) * m.stepsMilli[axis];
  return static_cast<int32_t>(n >= 0 ? (n + 500000) / 1000000 : -((-n + 500000) / 1000000));
}

uint32_t axisRate(const MotionModel& m, uint8_t axis) {
  const uint64_t r = static_cast<uint64_t>(m.vmaxUmS[axis]) * m.stepsMilli[axis] / 1000000u;
  return r > kEngineMaxRate ? kEngineMaxRate : static_cast<uint32_t>(r);
}

uint32_t axisAccel(const MotionModel& m, uint8_t axis) {
  return static_cast<uint32_t>(static_cast<uint64_t>(m.accelUmS2[axis]) * m.stepsMilli[axis] / 1000000u);
}

#ifndef __AVR__
namespace {
// Off the AVR (the host, and the app's work worker, which plans a million stops as WebAssembly), a
// memo of the moves priced last: neighbouring stops repeat the same few moves, and counting one
// segment by segment (stepTicks) took 60 % of planning a 1 M-cell board in `shortest` order. Keyed
// by the axes' limits as well, each thread its own. The Mega has no RAM for it: it plans a stop at a time.
struct PricedMove {
  uint32_t dx, dy, rate[2], accel[2], us;
};
constexpr uint32_t kPricedMoves = 1024;
#ifdef __wasm__
PricedMove tPriced[kPricedMoves];  // WebAssembly without threads: one
#else
thread_local PricedMove tPriced[kPricedMoves];
#endif
}  // namespace
#endif

uint32_t engineMoveUs(const MotionModel& m, uint32_t dx, uint32_t dy) {
  if (!dx && !dy) return 0;
#ifdef __AVR__
  const StepRamp p = stepRamp(dx, axisRate(m, 0), axisAccel(m, 0), dy, axisRate(m, 1), axisAccel(m, 1));
  return static_cast<uint32_t>((stepTicks(p, 0, p.total) + 1) / 2);
#else
  const uint32_t rx = axisRate(m, 0), ax = axisAccel(m, 0), ry = axisRate(m, 1), ay = axisAccel(m, 1);
  PricedMove& e = tPriced[(dx * 2654435761u ^ dy * 40503u) >> 22];
  if (e.dx == dx && e.dy == dy && e.rate[0] == rx && e.accel[0] == ax && e.rate[1] == ry && e.accel[1] == ay) return e.us;
  const StepRamp p = stepRamp(dx, rx, ax, dy, ry, ay);
  e = PricedMove{dx, dy, {rx, ry}, {ax, ay}, static_cast<uint32_t>((stepTicks(p, 0, p.total) + 1) / 2)};
  return e.us;
#endif
}

uint32_t engineMoveUs(const MotionModel& m, int32_t fromX, int32_t fromY, int32_t toX, int32_t toY) {
  const int32_t dx = axisSteps(m, 0, toX) - axisSteps(m, 0, fromX), dy = axisSteps(m, 1, toY) - axisSteps(m, 1, fromY);
  return engineMoveUs(m, static_cast<uint32_t>(dx < 0 ? -dx : dx), static_cast<uint32_t>(dy < 0 ? -dy : dy));
}

uint32_t moveTimeUs(uint32_t d, uint32_t v, uint32_t a) {
  if (d == 0) return 0;
  if (static_cast<uint64_t>(d) * a >= static_cast<uint64_t>(v) * v) {
    return static_cast<uint32_t>(roundDiv(static_cast<uint64_t>(d) * 1000000u, v) + roundDiv(static_cast<uint64_t>(v) * 1000000u, a));
  }
  return static_cast<uint32_t>(2 * isqrt64(static_cast<uint64_t>(d) * 1000000000000ull / a));
}

uint32_t fireLineUs(const uint32_t us[4], uint32_t baud) {
  uint32_t mask = 0, bytes = 7;  // "F:", the four commas, the newline
  for (uint8_t k = 0; k < 4; k++) {
    if (us[k]) mask |= 1u << k;
    uint32_t d = us[k];
    do bytes++; while (d /= 10);
  }
  if (!mask) return 0;
  bytes += mask >= 10 ? 2 : 1;
  return bytes * 10000000u / baud;
}

uint32_t stopCostUs(const MotionModel& m, int32_t fromX, int32_t fromY, int32_t toX, int32_t toY, const uint32_t us[4]) {
  return stopCostStepsUs(m, axisSteps(m, 0, toX) - axisSteps(m, 0, fromX), axisSteps(m, 1, toY) - axisSteps(m, 1, fromY), us);
}

uint32_t stopCostStepsUs(const MotionModel& m, int32_t dx, int32_t dy, const uint32_t us[4]) {
  const uint32_t move = engineMoveUs(m, static_cast<uint32_t>(dx < 0 ? -dx : dx), static_cast<uint32_t>(dy < 0 ? -dy : dy));
  uint32_t longest = 0;
  for (uint8_t k = 0; k < 4; k++)
    if (us[k] > longest) longest = us[k];
  return move + (move ? m.settleUs : 0) + m.overheadUs + fireLineUs(us, m.linkBaud) + longest;
}

void PlanClock::add(const Stop& s) {
  int32_t x = static_cast<int32_t>(h_.originUm[0]) + s.hx * static_cast<int32_t>(h_.pitchUm[0]);
  int32_t y = static_cast<int32_t>(h_.originUm[1]) + s.hy * static_cast<int32_t>(h_.pitchUm[1]);
  total_ += stopCostUs(m_, x_, y_, x, y, s.us);
  travel_[0] += absDiff(x, x_);
  travel_[1] += absDiff(y, y_);
  x_ = x;
  y_ = y;
}

}  // namespace uv
