// Trapezoidal move times and the per-stop clock of protocol/planner.md "Time model", in integer µs.
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

uint32_t moveTimeUs(uint32_t d, uint32_t v, uint32_t a) {
  if (d == 0) return 0;
  if (static_cast<uint64_t>(d) * a >= static_cast<uint64_t>(v) * v) {
    return static_cast<uint32_t>(roundDiv(static_cast<uint64_t>(d) * 1000000u, v) + roundDiv(static_cast<uint64_t>(v) * 1000000u, a));
  }
  return static_cast<uint32_t>(2 * isqrt64(static_cast<uint64_t>(d) * 1000000000000ull / a));
}

uint32_t stopCostUs(const Machine& m, int32_t fromX, int32_t fromY, int32_t toX, int32_t toY, uint32_t longestUs) {
  uint32_t tx = moveTimeUs(absDiff(toX, fromX), m.vmaxUmS[0], m.accelUmS2[0]);
  uint32_t ty = moveTimeUs(absDiff(toY, fromY), m.vmaxUmS[1], m.accelUmS2[1]);
  uint32_t move = tx > ty ? tx : ty;
  return move + (move ? m.settleUs : 0) + m.overheadUs + longestUs;
}

void PlanClock::add(const Stop& s) {
  int32_t x = static_cast<int32_t>(h_.originUm[0]) + s.hx * static_cast<int32_t>(h_.pitchUm[0]);
  int32_t y = static_cast<int32_t>(h_.originUm[1]) + s.hy * static_cast<int32_t>(h_.pitchUm[1]);
  uint32_t longest = 0;
  for (uint32_t us : s.us)
    if (us > longest) longest = us;
  total_ += stopCostUs(m_, x_, y_, x, y, longest);
  travel_[0] += absDiff(x, x_);
  travel_[1] += absDiff(y, y_);
  x_ = x;
  y_ = y;
}

}  // namespace uv
