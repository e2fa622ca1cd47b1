// Rest-to-rest trapezoidal motion in steps: each move's profile on its step-dominant axis, and the
// short constant-rate segments the step interrupt runs.
#include "step_profile.h"

#include "isqrt.h"  // one square root for the planner and the step engine

namespace mega {

using uv::isqrt32;

Profile profileFor(const uint32_t steps[3], const AxisLimits limits[3]) {
  Profile p{};
  for (uint8_t a = 0; a < 3; a++)
    if (steps[a] > p.total) p.total = steps[a];
  p.rate = kMaxStepRate;
  p.accel = 0xffffffffu;
  for (uint8_t a = 0; a < 3; a++) {
    if (!steps[a]) continue;
    // This axis moves steps[a] while the dominant one moves total: scale its limits up.
    uint64_t rate = static_cast<uint64_t>(limits[a].rate) * p.total / steps[a];
    uint64_t accel = static_cast<uint64_t>(limits[a].accel) * p.total / steps[a];
    if (rate < p.rate) p.rate = static_cast<uint32_t>(rate);
    if (accel < p.accel) p.accel = static_cast<uint32_t>(accel);
  }
  if (p.rate < kMinStepRate) p.rate = kMinStepRate;
  if (p.accel < 1) p.accel = 1;
  uint64_t twoA = 2ull * p.accel;
  p.rampSteps = static_cast<uint32_t>((static_cast<uint64_t>(p.rate) * p.rate + twoA - 1) / twoA);
  return p;
}

uint32_t rateAt(const Profile& p, uint32_t d2) {
  // v² = 2 a d = a d2. Below the ramp's end, a·d2 < rate² ≤ kMaxStepRate², which fits 32 bits.
  if (d2 >= 2 * p.rampSteps) return p.rate;
  uint32_t r = isqrt32(p.accel * d2);
  if (r > p.rate) r = p.rate;
  return r < kMinStepRate ? kMinStepRate : r;
}

uint32_t stoppingSteps(const Profile& p, uint32_t rate) {
  uint64_t twoA = 2ull * p.accel;
  return static_cast<uint32_t>((static_cast<uint64_t>(rate) * rate + twoA - 1) / twoA);
}

Segment nextSegment(const Profile& p, uint32_t done) {
  uint32_t remaining = p.total - done;
  if (remaining == 0) return Segment{0, 0};
  uint32_t fromStart = 2 * done + 1, fromEnd = 2 * remaining - 1;
  uint32_t r0 = rateAt(p, fromStart < fromEnd ? fromStart : fromEnd);
  uint32_t k = r0 / (1000000 / kSegmentUs);
  if (k < 1) k = 1;
  if (k > remaining) k = remaining;
  if (k > 0xffff) k = 0xffff;
  // Rate at the segment's middle, from whichever end is nearer.
  fromStart = 2 * done + k;
  fromEnd = 2 * remaining - k;
  uint32_t r = rateAt(p, fromStart < fromEnd ? fromStart : fromEnd);
  return Segment{static_cast<uint16_t>(k), static_cast<uint16_t>(kTickHz / r)};
}

}  // namespace mega
