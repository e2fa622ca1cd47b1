// A scan pass's stroke in steps: exact rational arithmetic, so the G's step and the mark agree to
// under a microsecond however long the stroke.
#include "scan_stroke.h"

#include "step_profile.h"

namespace mega {

namespace {
constexpr int64_t kStepDen = 2000000;  // positions ×2 µm × milli-steps/mm: steps = v / kStepDen
int64_t floorDiv(int64_t n, int64_t d) { return n >= 0 ? n / d : -((-n + d - 1) / d); }
int64_t ceilDiv(int64_t n, int64_t d) { return -floorDiv(-n, d); }
}  // namespace

bool strokeInterval(uint32_t windowUs, uint32_t pitchUm, uint32_t stepsMilli, uint16_t& interval, uint16_t& frac) {
  const uint64_t den = static_cast<uint64_t>(pitchUm) * stepsMilli;  // steps per window × 10⁶
  if (!den) return false;
  // 2W ticks a window: (2W × 10⁶ / den) ticks a step, ×65536, rounded.
  const uint64_t q16 = ((static_cast<uint64_t>(2 * static_cast<uint64_t>(windowUs)) * 1000000u << 16) + den / 2) / den;
  if (q16 < (static_cast<uint64_t>(kTickHz / kMaxStepRate) << 16) || q16 >= (1ull << 32)) return false;
  interval = static_cast<uint16_t>(q16 >> 16);
  frac = static_cast<uint16_t>(q16 & 0xffff);
  return true;
}

bool planStroke(const StrokeInput& in, StrokePlan& out) {
  if (!strokeInterval(in.windowUs, in.pitchUm, in.stepsMilli, out.interval, out.frac)) return false;
  const uint64_t i16 = (static_cast<uint64_t>(out.interval) << 16) | out.frac;
  // Work towards +X: a −X pass is its mirror image.
  const int64_t sign = in.descending ? -1 : 1;
  const int64_t mark = sign * in.markX2Um * static_cast<int64_t>(in.stepsMilli);  // steps × kStepDen
  const int64_t end = sign * in.endX2Um * static_cast<int64_t>(in.stepsMilli);
  out.leadUs = static_cast<uint16_t>(markLeadUs(in.linkBaud));
  const int64_t leadTicks16 = static_cast<int64_t>(2 * out.leadUs) << 16;
  // The G step: at least the lead before the mark at the exact speed; one step more in hand.
  const int64_t leadSteps = ceilDiv(leadTicks16, static_cast<int64_t>(i16)) + 1;
  const int64_t gAt = floorDiv(mark, kStepDen) - leadSteps;  // where the G step leaves the head
  out.markStep = in.rampSteps + 2;                             // in the middle: after the ramp's last
  const int64_t start = gAt - out.markStep;
  const int64_t stop = ceilDiv(end, kStepDen) + in.rampSteps + 1;
  // From the G step to the mark: (mark − gAt) steps of i16; then less the lead, in µs (ticks / 2).
  const int64_t ticks16 = static_cast<int64_t>((static_cast<uint64_t>(mark - gAt * kStepDen) * i16) / kStepDen);
  out.shiftUs = static_cast<uint32_t>(((ticks16 - leadTicks16) / 2 + 32768) >> 16);
  out.startSteps = static_cast<int32_t>(sign * start);
  out.steps = static_cast<int32_t>(sign * (stop - start));
  // The middle: every step but the ramps', at the exact interval.
  const uint64_t middle = static_cast<uint64_t>(stop - start) - 2 * in.rampSteps;
  return middle * i16 < (1ull << 48);
}

void strokeJump(const StrokePlan& k, uint32_t windowUs, uint32_t window, uint32_t windows, uint32_t flyUs, uint32_t& from,
                uint32_t& steps, uint32_t& savedTicks) {
  // Step markStep − 1 + n comes n × i16 / 65536 ticks after the G's step, were nothing flown, and the
  // plan's time 0 is leadUs + shiftUs after it: window w starts 2 × (that + w × W) ticks after.
  const uint64_t i16 = (static_cast<uint64_t>(k.interval) << 16) | k.frac;
  const uint64_t lead = k.leadUs + k.shiftUs;
  const uint64_t t0 = 2 * (lead + static_cast<uint64_t>(window) * windowUs) << 16;
  const uint64_t t1 = 2 * (lead + static_cast<uint64_t>(window + windows) * windowUs) << 16;
  from = k.markStep - 1 + static_cast<uint32_t>(t0 / i16);
  steps = k.markStep - 1 + static_cast<uint32_t>((t1 + i16 - 1) / i16) - from;
  savedTicks = 2 * (windows * windowUs - flyUs);
}

}  // namespace mega
