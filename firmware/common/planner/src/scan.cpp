// The scan planner (protocol/planner.md "Scan mode"): passes exposed on the move, one pass at a time from a CellSource.
#include "scan.h"

#include "scan_program.h"

#include <string.h>

namespace uv {

namespace {
uint64_t ceilDiv(uint64_t n, uint64_t d) { return (n + d - 1) / d; }
uint64_t roundDiv(uint64_t n, uint64_t d) { return (2 * n + d) / (2 * d); }
int64_t floorDiv(int64_t n, int64_t d) { return n >= 0 ? n / d : -((-n + d - 1) / d); }
}  // namespace

bool engineStep(const MotionModel& m, uint32_t pitchUm, uint32_t windowUs, uint64_t& q16) {
  const uint64_t den = static_cast<uint64_t>(pitchUm) * m.stepsMilli[0];
  if (!den) return false;
  q16 = (((2ull * windowUs * 1000000u) << 16) + den / 2) / den;
  return q16 >= (static_cast<uint64_t>(kEngineTickHz / kEngineMaxRate) << 16) && q16 < (1ull << 32);
}

void planStroke(const MotionModel& m, int32_t markX2Um, int32_t endX2Um, bool descending, uint64_t q16, uint32_t savedUs, ScanPass& out) {
  const int64_t sign = descending ? -1 : 1, S = m.stepsMilli[0], den = 2000000;  // positions in steps × den
  uint64_t rate = ((static_cast<uint64_t>(kEngineTickHz) << 16) + q16 - 1) / q16;  // Motion::strokeProfile
  if (rate > kEngineMaxRate) rate = kEngineMaxRate;
  const uint32_t accel = axisAccel(m, 0);
  const uint32_t ramp = stepRamp(1, static_cast<uint32_t>(rate), accel, 0, 0, 0).ramp;
  // The G step: at least the lead before the mark, one step more in hand, after the ramp and a step.
  const int64_t mark = sign * markX2Um * S;
  const int64_t gAt = floorDiv(mark, den) - static_cast<int64_t>(ceilDiv((2ull * strokeMarkLeadUs(m.linkBaud)) << 16, q16)) - 1;
  const int64_t start = gAt - (ramp + 2);
  const int64_t stop = -floorDiv(-(sign * endX2Um * S), den) + ramp + 1;
  out.startSteps = static_cast<int32_t>(sign * start);
  out.stopSteps = static_cast<int32_t>(sign * stop);
  const uint32_t n = static_cast<uint32_t>(stop - start);
  const StepRamp p = stepRamp(n, static_cast<uint32_t>(rate), accel, 0, 0, 0);
  const uint64_t up = stepTicks(p, 0, ramp), down = stepTicks(p, n - ramp, n);
  const uint64_t ticks = up + ((static_cast<uint64_t>(n - 2 * ramp) * q16) >> 16) + down;
  out.strokeUs = static_cast<uint32_t>((ticks - 2ull * savedUs + 1) / 2);
  // The run-out: from the last window's end (at least a step before the ramp down) to rest.
  out.runOutUs = static_cast<uint32_t>((down + (q16 >> 16) + 1) / 2);
  out.endUs = out.runOutUs >= kScanPassEndUs ? 0 : kScanPassEndUs - out.runOutUs;
  // The G step comes after the ramp and one step at the speed; the mark, (mark − gAt) steps later.
  const uint64_t markTicks16 = (up << 16) + q16 + static_cast<uint64_t>(mark - gAt * den) * q16 / den;
  out.markUs = static_cast<uint32_t>((markTicks16 + 65536) / 131072);
}

ScanMotion scanMotion(const JobHeader& h, const Durations& dose, const MotionModel& m) {
  ScanMotion out{0, 0, 0, 0};
  uint32_t longest = 0;
  for (uint8_t k = 0; k < 4; k++)
    if (dose.us(k, 255) > longest) longest = dose.us(k, 255);
  if (longest == 0) return out;
  uint64_t w = ceilDiv(static_cast<uint64_t>(h.pitchUm[0]) * 1000000u, m.vmaxUmS[0]);
  if (w < longest) w = longest;
  return passMotion(h, m, static_cast<uint32_t>(w));
}

ScanMotion passMotion(const JobHeader& h, const MotionModel& m, uint32_t windowUs) {
  const uint64_t p = h.pitchUm[0], w = windowUs;
  const uint64_t tA = ceilDiv(p * 1000000000000ull, static_cast<uint64_t>(m.accelUmS2[0]) * w);
  ScanMotion out;
  out.windowUs = windowUs;
  out.speedUmS = static_cast<uint32_t>(roundDiv(p * 1000000u, w));
  out.accelUs = static_cast<uint32_t>(tA);
  out.overscanUm = static_cast<uint32_t>(ceilDiv(p * tA, 2 * w));
  return out;
}

ScanPlanner::ScanPlanner(const JobHeader& h, CellSource& cells, const MotionModel& m)
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
  return !(mode_ & kNeverFly) && pass_.windowUs > ceilDiv(static_cast<uint64_t>(h_.pitchUm[0]) * 1000000u, m_.vmaxUmS[0]);
}

uint64_t ScanPlanner::switchSpan() const {
  int32_t dxMin = h_.offsets[0][0], dxMax = dxMin;
  for (uint8_t k = 1; k < 4; k++) {
    if (h_.offsets[k][0] < dxMin) dxMin = h_.offsets[k][0];
    if (h_.offsets[k][0] > dxMax) dxMax = h_.offsets[k][0];
  }
  return static_cast<uint64_t>(h_.cols + dxMax - dxMin);
}

bool ScanPlanner::supported() const {
  return refusal_ != Refusal::TooLong && dyMax_ - dyMin_ < static_cast<int16_t>(kCoveredWindowRows) && switchSpan() * motion().windowUs < (1ull << 32);
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
  flownSpan(first, last, span);  // every stretch kept flies (consider())
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
  }
  started_ = false;
  jumpNext_ = 0;
  memset(&u_, 0, sizeof u_);
}

// Plays the open pass's events through the program writer and reopens it: true when its chain
// outruns the printhead link (need > have, uv::LinkLoad), as the Mega checks at M29.
bool ScanPlanner::outrunsLink(uint64_t& need, uint64_t& have) {
#ifndef __AVR__
  replay_ = false;
  logging_ = log_ != nullptr;
  logged_ = logNext_ = 0;
#endif
  ProgramLines lines(passEvent, this);
  LinkLoad load(m_.linkBaud);
  char line[kNanoMaxLine + 2];
  for (uint8_t n; (n = lines.next(line)) != 0;) load.add(line, n, lines.lastUs());
  // The pass's last event (every LED off) is the last moment nextEvent() gathered.
  const uint32_t lastUs = u_.ev.heldT;
  openPass();
#ifndef __AVR__
  // Every event logged, none left unread by an early end: the pass's events as nextEvent() would walk them.
  replay_ = logging_ && !lines.failed() && logged_ <= log_->cap;
  logging_ = false;
  chainBytes_ = load.bytes();
  chainAheadBytes_ = load.aheadBytes();
#endif
  if (lines.failed()) return false;  // a gap of 2²⁸ µs: the Mega refuses the pass, whatever its speed
  return !load.fits(lastUs, need, have);
}

// S(n − 1) + W: every window, less what each flown stretch saves.
bool ScanPlanner::flownSpan(int32_t first, int32_t last, uint64_t& span) {
  span = static_cast<uint64_t>(last - first + 1) * pass_.windowUs;
  for (uint8_t i = 0; i < jumpCount_; i++) {
    const uint32_t f = fly(jumpG_[i]);
    if (!f) return false;
    span -= static_cast<uint64_t>(jumpG_[i]) * pass_.windowUs - f;
  }
  return true;
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
bool ScanPlanner::nextLitWindow(uint32_t& j, bool intervals) {
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
        if (intervals) {
          u_.iv.jumpReady = true;
          u_.iv.jumpWindow = window;
          u_.iv.jumpWindows = windows;
          u_.iv.jumpUs = f;
        }
      }
    }
  }
  started_ = true;
  lastJ_ = j;
  lastS_ = s;
  for (uint8_t k = 0; k < 4; k++) {
    if (!intervals) u_.ev.winUs[k] = 0;
    if (!isLive(k) || hx_[k] != best) continue;
    if (!intervals) {
      u_.ev.winUs[k] = us_[k];
      peek(k);
      continue;
    }
    const uint32_t on = s + (w - us_[k]) / 2, off = on + us_[k];
    if (isPending(k) && u_.iv.pendOff[k] == on) {
      u_.iv.pendOff[k] = off;  // touching: the LED stays on
    } else {
      if (isPending(k)) {
        u_.iv.ready |= static_cast<uint8_t>(1 << k);
        u_.iv.readyOn[k] = u_.iv.pendOn[k];
        u_.iv.readyOff[k] = u_.iv.pendOff[k];
      }
      setPending(k, true);
      u_.iv.pendOn[k] = on;
      u_.iv.pendOff[k] = off;
    }
    peek(k);
  }
  return true;
}

bool ScanPlanner::next(ScanEvent& out) {
  for (;;) {
    if (u_.iv.jumpReady) {
      u_.iv.jumpReady = false;
      out = ScanEvent{true, 0, 0, 0, u_.iv.jumpWindow, u_.iv.jumpWindows, u_.iv.jumpUs};
      return true;
    }
    for (uint8_t k = 0; k < 4; k++) {
      if (!(u_.iv.ready & (1 << k))) continue;
      u_.iv.ready &= static_cast<uint8_t>(~(1 << k));
      out = ScanEvent{false, k, u_.iv.readyOn[k], u_.iv.readyOff[k], 0, 0, 0};
      return true;
    }
    uint32_t j;
    if (nextLitWindow(j, true)) continue;
    for (uint8_t k = 0; k < 4; k++) {  // the pass's end closes every open interval
      if (!isPending(k)) continue;
      setPending(k, false);
      out = ScanEvent{false, k, u_.iv.pendOn[k], u_.iv.pendOff[k], 0, 0, 0};
      return true;
    }
    return false;
  }
}

// The next lit window's edges, in time order (insertion sort of at most 8).
bool ScanPlanner::fillEdges() {
  uint32_t j;
  if (!nextLitWindow(j, false)) return false;
  u_.ev.edgeCount = u_.ev.edgeNext = 0;
  const uint32_t w = pass_.windowUs;
  for (uint8_t k = 0; k < 4; k++) {
    if (!u_.ev.winUs[k]) continue;
    const uint32_t on = lastS_ + (w - u_.ev.winUs[k]) / 2;
    const Edge two[2] = {{on, k, true}, {on + u_.ev.winUs[k], k, false}};
    for (const Edge& e : two) {
      uint8_t i = u_.ev.edgeCount++;
      while (i > 0 && u_.ev.edges[i - 1].t > e.t) {
        u_.ev.edges[i] = u_.ev.edges[i - 1];
        i--;
      }
      u_.ev.edges[i] = e;
    }
  }
  return true;
}

#ifndef __AVR__
bool ScanPlanner::passEvent(void* ctx, uint32_t& t, uint8_t& m) {
  ScanPlanner& p = *static_cast<ScanPlanner*>(ctx);
  if (!p.nextEvent(t, m)) return false;
  if (p.logging_ && p.logged_ < p.log_->cap) {
    p.log_->t[p.logged_] = t;
    p.log_->state[p.logged_] = m;
  }
  if (p.logging_ && p.logged_ <= p.log_->cap) p.logged_++;
  return true;
}
#endif

// Gathers every edge of one moment before handing out the state after it: an LED whose cell ends
// where its next cell begins (full cells at an uncapped speed) switches off and on at the same
// moment, which is no event at all.
bool ScanPlanner::nextEvent(uint32_t& t, uint8_t& m) {
#ifndef __AVR__
  if (replay_) {
    if (logNext_ == logged_) return false;
    t = log_->t[logNext_];
    m = log_->state[logNext_++];
    return true;
  }
#endif
  for (;;) {
    const bool more = u_.ev.edgeNext < u_.ev.edgeCount || fillEdges();
    if (u_.ev.held && (!more || u_.ev.edges[u_.ev.edgeNext].t > u_.ev.heldT)) {
      u_.ev.held = false;
      if (u_.ev.state != u_.ev.emitted) {
        u_.ev.emitted = u_.ev.state;
        t = u_.ev.heldT;
        m = u_.ev.state;
        return true;
      }
    }
    if (!more) return false;
    const Edge& e = u_.ev.edges[u_.ev.edgeNext++];
    const uint8_t bit = static_cast<uint8_t>(1 << e.led);
    u_.ev.state = e.on ? static_cast<uint8_t>(u_.ev.state | bit) : static_cast<uint8_t>(u_.ev.state & ~bit);
    u_.ev.heldT = e.t;
    u_.ev.held = true;
  }
}

}  // namespace uv
