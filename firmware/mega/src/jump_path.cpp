// A flown stretch's path in time: see jump_path.h.
#include "jump_path.h"

#include <math.h>

namespace mega {

// With speed-up e = u − v at acceleration a over T ticks and N steps (cruise in the middle):
//   T = 2e/a + tc,  N = (u² − v²)/a + u·tc   ⇒   e² − a·T·e + a·(N − v·T) = 0,
// whose smaller root is the path (the larger would speed up past the middle). Written as
// 2c / (B + √(B² − 4c)) it keeps its digits when the speed-up is small.
void JumpPath::plan(uint32_t steps, uint32_t ticks, float rate, float accel) {
  n_ = steps;
  j_ = ticks;
  v_ = rate;
  a_ = accel;
  const float T = static_cast<float>(ticks), extra = static_cast<float>(steps) - rate * T;  // steps beyond cruising at v
  if (extra <= 0 || ticks == 0) {  // nothing to gain: cross at the one speed that fits
    v_ = ticks ? static_cast<float>(steps) / T : rate;
    a_ = t1_ = 0;
    return;
  }
  const float c = accel * extra, B = accel * T, disc = B * B - 4 * c;
  float e;
  if (disc <= 0) {  // a triangle even at a: take the acceleration that fits exactly
    a_ = 4 * extra / (T * T);
    e = a_ * T / 2;
  } else {
    e = 2 * c / (B + sqrtf(disc));
  }
  t1_ = e / a_;
  if (t1_ > T / 2) t1_ = T / 2;
}

float JumpPath::lead(float x) const {
  // x = v·t + a·t²/2  ⇒  t = 2x / (v + √(v² + 2a·x)), exact near 0 as well.
  return 2 * x / (v_ + sqrtf(v_ * v_ + 2 * a_ * x));
}

float JumpPath::at(uint32_t x) const {
  if (x >= n_) return static_cast<float>(j_);
  const float fx = static_cast<float>(x), N = static_cast<float>(n_);
  if (a_ == 0) return fx / v_;
  const float x1 = (v_ + a_ * t1_ / 2) * t1_;  // the speed-up's steps
  if (fx <= x1) return lead(fx);
  if (fx < N - x1) return t1_ + (fx - x1) / peak();
  return static_cast<float>(j_) - lead(N - fx);  // the slow-down mirrors the speed-up
}

}  // namespace mega
