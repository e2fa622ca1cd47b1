// A mixed job's passes of stops in the scan planner (protocol/planner.md "Mixed mode"): their price
// from where the head stands, and their stops one at a time, from the open pass's four cursors.
#include "scan.h"

namespace uv {

// The open pass as stops from where the head stands (planner.md "Mixed mode"): their time, and the
// last one's X in steps.
uint64_t ScanPlanner::priceStops(int32_t hy, int32_t& endX) {
  openPass();
  setStopPass(true);
  const int32_t y = axisSteps(m_, 1, Y(hy));
  int32_t x = curX_, from = axisSteps(m_, 1, curY_);
  uint64_t total = 0;
  Stop s;
  while (nextStop(s)) {
    const int32_t to = axisSteps(m_, 0, X(s.hx));
    total += stopCostStepsUs(m_, to - x, y - from, s.us);
    x = to;
    from = y;
  }
  endX = x;
  return total;
}

bool ScanPlanner::nextStop(Stop& out) {
  if (!stopPass()) return false;
  if (live_ & kBandBit) return bandNextStop(out);
  bool any = false;
  int32_t best = 0;
  for (uint8_t k = 0; k < 4; k++)
    if (isLive(k) && (!any || (descending_ ? hx_[k] > best : hx_[k] < best))) {
      best = hx_[k];
      any = true;
    }
  if (!any) {
    setStopPass(false);
    return false;
  }
  out.hx = best;
  for (uint8_t k = 0; k < 4; k++) {
    out.us[k] = 0;
    if (row_[k] >= 0) out.hy = row_[k] - h_.offsets[k][1];  // the pass's head row (no byte kept for it)
    if (!isLive(k) || hx_[k] != best) continue;
    out.us[k] = us_[k];
    peek(k);
  }
  return true;
}

}  // namespace uv
