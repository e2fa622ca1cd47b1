// The scan planner (protocol/planner.md "Scan mode"): passes exposed on the move, one pass at a time from a CellSource.
#include "scan.h"

#include "scan_program.h"

namespace uv {

namespace {
uint64_t ceilDiv(uint64_t n, uint64_t d) { return (n + d - 1) / d; }
uint64_t roundDiv(uint64_t n, uint64_t d) { return (2 * n + d) / (2 * d); }
int64_t floorDiv(int64_t n, int64_t d) { return n >= 0 ? n / d : -((-n + d - 1) / d); }
}  // namespace

bool engineStep(const Machine& m, uint32_t pitchUm, uint32_t windowUs, uint64_t& q16) {
  const uint64_t den = static_cast<uint64_t>(pitchUm) * m.stepsMilli[0];
  if (!den) return false;
  q16 = (((2ull * windowUs * 1000000u) << 16) + den / 2) / den;
  return q16 >= (static_cast<uint64_t>(kEngineTickHz / kEngineMaxRate) << 16) && q16 < (1ull << 32);
}

void planStroke(const Machine& m, int32_t markX2Um, int32_t endX2Um, bool descending, uint64_t q16, uint32_t savedUs, ScanPass& out) {
  const int64_t sign = descending ? -1 : 1, S = m.stepsMilli[0], den = 2000000;  // positions in steps × den
  uint64_t rate = ((static_cast<uint64_t>(kEngineTickHz) << 16) + q16 - 1) / q16;  // Motion::strokeProfile
  if (rate > kEngineMaxRate) rate = kEngineMaxRate;
  const uint32_t accel = axisAccel(m, 0);
  const uint32_t ramp = stepRamp(1, static_cast<uint32_t>(rate), accel, 0, 0, 0).ramp;
  // The G step: at least the lead before the mark, one step more in hand, after the ramp and a step.
  const int64_t mark = sign * markX2Um * S;
  const int64_t gAt = floorDiv(mark, den) - static_cast<int64_t>(ceilDiv((2ull * kStrokeMarkLeadUs) << 16, q16)) - 1;
  const int64_t start = gAt - (ramp + 2);
  const int64_t stop = -floorDiv(-(sign * endX2Um * S), den) + ramp + 1;
  out.startSteps = static_cast<int32_t>(sign * start);
  out.stopSteps = static_cast<int32_t>(sign * stop);
  const uint32_t n = static_cast<uint32_t>(stop - start);
  const StepRamp p = stepRamp(n, static_cast<uint32_t>(rate), accel, 0, 0, 0);
  const uint64_t up = stepTicks(p, 0, ramp);
  const uint64_t ticks = up + ((static_cast<uint64_t>(n - 2 * ramp) * q16) >> 16) + stepTicks(p, n - ramp, n);
  out.strokeUs = static_cast<uint32_t>((ticks - 2ull * savedUs + 1) / 2);
  // The G step comes after the ramp and one step at the speed; the mark, (mark − gAt) steps later.
  const uint64_t markTicks16 = (up << 16) + q16 + static_cast<uint64_t>(mark - gAt * den) * q16 / den;
  out.markUs = static_cast<uint32_t>((markTicks16 + 65536) / 131072);
}

ScanMotion scanMotion(const JobHeader& h, const Durations& dose, const Machine& m) {
  ScanMotion out{0, 0, 0, 0};
  uint32_t longest = 0;
  for (uint8_t k = 0; k < 4; k++)
    if (dose.us(k, 255) > longest) longest = dose.us(k, 255);
  if (longest == 0) return out;
  uint64_t w = ceilDiv(static_cast<uint64_t>(h.pitchUm[0]) * 1000000u, m.vmaxUmS[0]);
  if (w < longest) w = longest;
  return passMotion(h, m, static_cast<uint32_t>(w));
}

ScanMotion passMotion(const JobHeader& h, const Machine& m, uint32_t windowUs) {
  const uint64_t p = h.pitchUm[0], w = windowUs;
  const uint64_t tA = ceilDiv(p * 1000000000000ull, static_cast<uint64_t>(m.accelUmS2[0]) * w);
  ScanMotion out;
  out.windowUs = windowUs;
  out.speedUmS = static_cast<uint32_t>(roundDiv(p * 1000000u, w));
  out.accelUs = static_cast<uint32_t>(tA);
  out.overscanUm = static_cast<uint32_t>(ceilDiv(p * tA, 2 * w));
  return out;
}

ScanPlanner::ScanPlanner(const JobHeader& h, CellSource& cells, const Machine& m)
    : h_(h), cells_(cells), m_(m), dose_(h), known_(h.rows), curX_(axisSteps(m, 0, m.startUm[0])), curY_(m.startUm[1]),
      flies_(false), pass_(scanMotion(h, dose_, m)) {
  dyMin_ = dyMax_ = h.offsets[0][1];
  for (uint8_t k = 1; k < 4; k++) {
    if (h.offsets[k][1] < dyMin_) dyMin_ = h.offsets[k][1];
    if (h.offsets[k][1] > dyMax_) dyMax_ = h.offsets[k][1];
  }
}

// The LED's next cell with light in the cursor's direction: its head column and on-time.
bool ScanPlanner::readLit(uint8_t led, int32_t& hx, uint32_t& us) {
  uint16_t col;
  uint8_t value;
  while (cells_.next(led, col, value)) {
    us = dose_.us(led, value);
    if (us == 0) continue;
    hx = static_cast<int32_t>(col) - h_.offsets[led][0];
    return true;
  }
  return false;
}

bool ScanPlanner::mayFly() const {
  return !neverFly_ && pass_.windowUs > ceilDiv(static_cast<uint64_t>(h_.pitchUm[0]) * 1000000u, m_.vmaxUmS[0]);
}

bool ScanPlanner::supported() const {
  int32_t dxMin = h_.offsets[0][0], dxMax = dxMin;
  for (uint8_t k = 1; k < 4; k++) {
    if (h_.offsets[k][0] < dxMin) dxMin = h_.offsets[k][0];
    if (h_.offsets[k][0] > dxMax) dxMax = h_.offsets[k][0];
  }
  const uint64_t span = static_cast<uint64_t>(h_.cols + dxMax - dxMin);
  return refusal_ != Refusal::TooLong && dyMax_ - dyMin_ < static_cast<int16_t>(kCoveredWindowRows) && span * motion().windowUs < (1ull << 32);
}

bool ScanPlanner::nextPass(ScanPass& out) {
  starved_ = false;
  if (!supported() || refused() || motion().windowUs == 0) return false;
  for (; scan_ < h_.rows; uncover(scan_), scan_++) {
    const uint16_t r = scan_;
    low_ = r;
    // A pass opened here reads the rows up to r + (dyMax − dyMin): they must all have arrived.
    if (known_ < h_.rows && static_cast<int32_t>(r) + (dyMax_ - dyMin_) >= static_cast<int32_t>(known_)) {
      starved_ = true;
      return false;
    }
    if (covered(r) || !cells_.rowNonEmpty(r)) continue;
    // The rows of this pass, as planner.md "Passes" gives them (the same as the stop planner's).
    const int32_t hy = static_cast<int32_t>(r) - dyMin_;
    for (uint8_t k = 0; k < 4; k++) {
      row_[k] = -1;
      const int32_t rk = hy + h_.offsets[k][1];
      if (rk < 0 || rk >= h_.rows || covered(rk)) continue;
      cover(rk);
      row_[k] = static_cast<int16_t>(rk);
    }
    pass_ = motion();  // the job's window first
    int32_t first, last;
    uint64_t span;
    if (!layout(first, last, span)) continue;  // no lit cell: the pass is dropped
    uncover(scan_);
    scan_++;
    descending_ = passes_ % 2 == 1;
    start_ = descending_ ? last : first;
    openPass();
    // The link cap (planner.md "The printhead link"): a pass whose program lines would outrun the
    // link is laid out again at a longer window, until they fit.
    for (uint64_t need, have; outrunsLink(need, have);) {
      uint64_t w = have ? ceilDiv(static_cast<uint64_t>(pass_.windowUs) * need, have) : 2ull * pass_.windowUs;
      if (w <= pass_.windowUs) w = pass_.windowUs + 1ull;
      int32_t dxMin = h_.offsets[0][0], dxMax = dxMin;
      for (uint8_t k = 1; k < 4; k++) {
        if (h_.offsets[k][0] < dxMin) dxMin = h_.offsets[k][0];
        if (h_.offsets[k][0] > dxMax) dxMax = h_.offsets[k][0];
      }
      if (static_cast<uint64_t>(h_.cols + dxMax - dxMin) * w >= (1ull << 32)) {
        refusal_ = Refusal::TooLong;
        return false;
      }
      pass_ = uv::passMotion(h_, m_, static_cast<uint32_t>(w));
      layout(first, last, span);
      openPass();
    }
    const int32_t reach = static_cast<int32_t>((h_.pitchUm[0] + 1) / 2 + pass_.overscanUm);
    out.hy = hy;
    out.descending = descending_;
    out.first = first;
    out.last = last;
    out.runUpUm = descending_ ? X(last) + reach : X(first) - reach;
    out.runOutUm = descending_ ? X(first) - reach : X(last) + reach;
    // The pass as the Mega runs it (planner.md "The stroke"): the step engine's move to the stroke's
    // start, the overhead, the stroke, and the Nano's Q answer that confirms the pass.
    uint64_t q16;
    if (!engineStep(m_, h_.pitchUm[0], pass_.windowUs, q16)) {
      refusal_ = Refusal::Engine;  // the job's window, or a pass the link cap slowed, is beyond the step engine
      return false;
    }
    const int32_t pitch = static_cast<int32_t>(h_.pitchUm[0]), dir = descending_ ? -1 : 1;
    const int32_t x0 = X(descending_ ? last : first), x1 = X(descending_ ? first : last);
    const uint64_t saved = static_cast<uint64_t>(last - first + 1) * pass_.windowUs - span;
    planStroke(m_, 2 * x0 - dir * pitch, 2 * x1 + dir * pitch, descending_, q16, static_cast<uint32_t>(saved), out);
    const int32_t y = Y(out.hy), dy = axisSteps(m_, 1, y) - axisSteps(m_, 1, curY_), dx = out.startSteps - curX_;
    out.moveUs = engineMoveUs(m_, static_cast<uint32_t>(dx < 0 ? -dx : dx), static_cast<uint32_t>(dy < 0 ? -dy : dy));
    out.scanUs = static_cast<uint64_t>(out.moveUs) + kScanPassLoadUs + out.strokeUs + kScanPassEndUs;
    out.stopsUs = 0;
    out.stops = false;
    int32_t endX = out.stopSteps;
    if (h_.strategy == Strategy::Mixed) {  // planner.md "Mixed mode": the stops when they cost no more than the stroke
      out.stopsUs = priceStops(hy, endX);
      out.stops = out.stopsUs <= out.scanUs;
      openPass();  // the cursors again, for the events or the stops
      setStopPass(out.stops);
    }
    estimate_ += out.stops ? out.stopsUs : out.scanUs;
    curX_ = out.stops ? endX : out.stopSteps;
    curY_ = y;
    passes_++;
    return true;
  }
  return false;
}

// The open pass's lit windows at the window pass_, ascending: its extent, the stretches it flies,
// and S(n − 1) + W. False when it has no lit cell.
bool ScanPlanner::layout(int32_t& first, int32_t& last, uint64_t& span) {
  flies_ = mayFly();
  first = INT32_MAX;
  last = INT32_MIN;
  for (uint8_t k = 0; k < 4; k++) {
    setLive(k, false);
    if (row_[k] < 0) continue;
    cells_.open(k, static_cast<uint16_t>(row_[k]), false);
    peek(k);
  }
  jumpCount_ = jumpNext_ = 0;
  for (;;) {
    bool any = false;
    int32_t best = 0;
    for (uint8_t k = 0; k < 4; k++)
      if (isLive(k) && (!any || hx_[k] < best)) {
        best = hx_[k];
        any = true;
      }
    if (!any) break;
    if (first > last) {
      first = first_ = best;  // consider() keeps columns from it
    } else if (best - last > 1 && best - last - 1 <= 0xffff) {
      consider(last + 1, static_cast<uint16_t>(best - last - 1));
    }
    last = best;
    for (uint8_t k = 0; k < 4; k++)
      if (isLive(k) && hx_[k] == best) peek(k);
  }
  if (first > last) return false;
  // S(n − 1) + W: every window, less what each flown stretch saves.
  span = static_cast<uint64_t>(last - first + 1) * pass_.windowUs;
  for (uint8_t i = 0; i < jumpCount_; i++) span -= static_cast<uint64_t>(jumpG_[i]) * pass_.windowUs - fly(jumpG_[i]);
  for (uint8_t i = 1; i < jumpCount_; i++)  // by column, ascending
    for (uint8_t k = i; k > 0 && jumpCol_[k - 1] > jumpCol_[k]; k--) {
      const uint16_t c = jumpCol_[k], g = jumpG_[k];
      jumpCol_[k] = jumpCol_[k - 1];
      jumpG_[k] = jumpG_[k - 1];
      jumpCol_[k - 1] = c;
      jumpG_[k - 1] = g;
    }
  return true;
}

// Opens the pass's cursors in its direction and clears what next() and nextEvent() hand out.
void ScanPlanner::openPass() {
  for (uint8_t k = 0; k < 4; k++) {
    setLive(k, false);
    if (row_[k] < 0) continue;
    cells_.open(k, static_cast<uint16_t>(row_[k]), descending_);
    peek(k);
    setPending(k, false);
  }
  started_ = false;
  ready_ = 0;
  jumpNext_ = 0;
  jumpReady_ = false;
  edgeCount_ = edgeNext_ = 0;
  held_ = false;
  state_ = emitted_ = 0;
}

// Plays the open pass's events through the program writer and reopens it: true when its chain
// outruns the printhead link (need > have, uv::LinkLoad), as the Mega checks at M29.
bool ScanPlanner::outrunsLink(uint64_t& need, uint64_t& have) {
  ProgramLines lines(passEvent, this);
  LinkLoad load;
  char line[kNanoMaxLine + 2];
  for (uint8_t n; (n = lines.next(line)) != 0;) load.add(line, n, lines.lastUs());
  // The pass's last event (every LED off) is the last moment nextEvent() gathered.
  const uint32_t lastUs = heldT_;
  openPass();
  if (lines.failed()) return false;  // a gap of 2²⁸ µs: the Mega refuses the pass, whatever its speed
  return !load.fits(lastUs, need, have);
}

// F(g) when flying g blank windows saves at least a window, F(g) ≤ (g − 1)·W, else 0.
uint32_t ScanPlanner::fly(uint32_t g) {
  if (!flies_) return 0;
  const int64_t move = moveTimeUs(g * h_.pitchUm[0] + 2 * pass_.overscanUm, m_.vmaxUmS[0], m_.accelUmS2[0]);
  int64_t f = move - 2 * static_cast<int64_t>(pass_.accelUs);
  if (f < 1) f = 1;
  return static_cast<uint64_t>(f) <= static_cast<uint64_t>(g - 1) * pass_.windowUs ? static_cast<uint32_t>(f) : 0;
}

// A blank stretch of g windows from head column `col` up, met in the ascending walk: it joins the
// flown ones if it may be flown and is among the kMaxJumps longest (the lower column first on a tie,
// so a later one of equal length never displaces one kept).
void ScanPlanner::consider(int32_t col, uint16_t g) {
  uint8_t slot = jumpCount_;
  if (jumpCount_ == kMaxJumps) {
    slot = 0;  // the shortest kept, the highest column among equals
    for (uint8_t i = 1; i < kMaxJumps; i++)
      if (jumpG_[i] < jumpG_[slot] || (jumpG_[i] == jumpG_[slot] && jumpCol_[i] > jumpCol_[slot])) slot = i;
    if (g <= jumpG_[slot]) return;  // before timing its fly: on the Mega that is the costly part
  }
  if (!fly(g)) return;
  if (slot == jumpCount_) jumpCount_++;
  jumpCol_[slot] = static_cast<uint16_t>(col - first_);
  jumpG_[slot] = g;
}

void ScanPlanner::stretch(uint8_t i, uint32_t& window, uint32_t& windows) const {
  const uint8_t k = descending_ ? static_cast<uint8_t>(jumpCount_ - 1 - i) : i;
  windows = jumpG_[k];
  window = descending_ ? static_cast<uint32_t>(start_ - first_ - jumpCol_[k] - jumpG_[k] + 1) : jumpCol_[k];
}

void ScanPlanner::jump(uint8_t i, uint32_t& window, uint32_t& windows, uint32_t& flyUs) {
  stretch(i, window, windows);
  flyUs = fly(windows);
}

// Takes the pass's next lit window in its direction: its start S(j), a jump before it if flown, and
// its LEDs' cells, which extend or close each LED's open interval.
bool ScanPlanner::nextLitWindow(uint32_t& j) {
  bool any = false;
  int32_t best = 0;
  for (uint8_t k = 0; k < 4; k++)
    if (isLive(k) && (!any || (descending_ ? hx_[k] > best : hx_[k] < best))) {
      best = hx_[k];
      any = true;
    }
  if (!any) return false;
  const uint32_t w = pass_.windowUs;
  j = static_cast<uint32_t>(descending_ ? start_ - best : best - start_);
  uint32_t s = j * w;
  if (started_) {
    s = lastS_ + (j - lastJ_) * w;
    if (jumpNext_ < jumpCount_) {
      uint32_t window, windows;
      stretch(jumpNext_, window, windows);
      if (window == lastJ_ + 1 && windows == j - lastJ_ - 1) {  // this stretch is flown
        jumpNext_++;
        const uint32_t f = fly(windows);
        s = lastS_ + w + f;
        jumpReady_ = true;
        jumpWindow_ = window;
        jumpWindows_ = windows;
        jumpUs_ = f;
      }
    }
  }
  started_ = true;
  lastJ_ = j;
  lastS_ = s;
  for (uint8_t k = 0; k < 4; k++) {
    winUs_[k] = 0;
    if (!isLive(k) || hx_[k] != best) continue;
    winUs_[k] = us_[k];
    const uint32_t on = s + (w - us_[k]) / 2, off = on + us_[k];
    if (isPending(k) && pendOff_[k] == on) {
      pendOff_[k] = off;  // touching: the LED stays on
    } else {
      if (isPending(k)) {
        ready_ |= static_cast<uint8_t>(1 << k);
        readyOn_[k] = pendOn_[k];
        readyOff_[k] = pendOff_[k];
      }
      setPending(k, true);
      pendOn_[k] = on;
      pendOff_[k] = off;
    }
    peek(k);
  }
  return true;
}

bool ScanPlanner::next(ScanEvent& out) {
  for (;;) {
    if (jumpReady_) {
      jumpReady_ = false;
      out = ScanEvent{true, 0, 0, 0, jumpWindow_, jumpWindows_, jumpUs_};
      return true;
    }
    for (uint8_t k = 0; k < 4; k++) {
      if (!(ready_ & (1 << k))) continue;
      ready_ &= static_cast<uint8_t>(~(1 << k));
      out = ScanEvent{false, k, readyOn_[k], readyOff_[k], 0, 0, 0};
      return true;
    }
    uint32_t j;
    if (nextLitWindow(j)) continue;
    for (uint8_t k = 0; k < 4; k++) {  // the pass's end closes every open interval
      if (!isPending(k)) continue;
      setPending(k, false);
      out = ScanEvent{false, k, pendOn_[k], pendOff_[k], 0, 0, 0};
      return true;
    }
    return false;
  }
}

// The next lit window's edges, in time order (insertion sort of at most 8).
bool ScanPlanner::fillEdges() {
  uint32_t j;
  if (!nextLitWindow(j)) return false;
  edgeCount_ = edgeNext_ = 0;
  const uint32_t w = pass_.windowUs;
  for (uint8_t k = 0; k < 4; k++) {
    if (!winUs_[k]) continue;
    const uint32_t on = lastS_ + (w - winUs_[k]) / 2;
    const Edge two[2] = {{on, k, true}, {on + winUs_[k], k, false}};
    for (const Edge& e : two) {
      uint8_t i = edgeCount_++;
      while (i > 0 && edges_[i - 1].t > e.t) {
        edges_[i] = edges_[i - 1];
        i--;
      }
      edges_[i] = e;
    }
  }
  return true;
}

// Gathers every edge of one moment before handing out the state after it: an LED whose cell ends
// where its next cell begins (full cells at an uncapped speed) switches off and on at the same
// moment, which is no event at all.
bool ScanPlanner::nextEvent(uint32_t& t, uint8_t& m) {
  for (;;) {
    const bool more = edgeNext_ < edgeCount_ || fillEdges();
    if (held_ && (!more || edges_[edgeNext_].t > heldT_)) {
      held_ = false;
      if (state_ != emitted_) {
        emitted_ = state_;
        t = heldT_;
        m = state_;
        return true;
      }
    }
    if (!more) return false;
    const Edge& e = edges_[edgeNext_++];
    const uint8_t bit = static_cast<uint8_t>(1 << e.led);
    state_ = e.on ? static_cast<uint8_t>(state_ | bit) : static_cast<uint8_t>(state_ & ~bit);
    heldT_ = e.t;
    held_ = true;
  }
}

}  // namespace uv
