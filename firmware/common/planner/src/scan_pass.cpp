// Opening the scan planner's passes (protocol/planner.md "Passes", "Scan mode"): the next pass with
// a lit cell, and a pass laid out, link-capped, stroked and priced from where the head stands.
#include "scan.h"

#include "glide.h"

namespace uv {

namespace {
uint64_t ceilDiv(uint64_t n, uint64_t d) { return (n + d - 1) / d; }
}  // namespace

bool ScanPlanner::nextPass(ScanPass& out, const KeptPass* kept) {
  starved_ = false;
  if (!supported() || refused() || motion().windowUs == 0) return false;
  live_ = static_cast<uint8_t>(live_ & ~(kStopPassBit | kBandBit));
  if (h_.strategy == Strategy::Mixed) return nextBand(out);
  int32_t hy, first, last;
  uint64_t span;
  bool restored = false;
  return collect(hy, first, last, span, kept, &restored) && planPass(hy, first, last, span, out, restored);
}

void ScanPlanner::keep(const ScanPass& p, KeptPass& out) const {
  out.windowUs = pass_.windowUs;
  out.hy = p.hy;
  out.first = first_;
  out.last = p.last;
  for (uint8_t i = 0; i < kMaxJumps; i++) {
    out.jumpCol[i] = i < jumpCount_ ? jumpCol_[i] : 0;
    out.jumpG[i] = i < jumpCount_ ? jumpG_[i] : 0;
  }
}

// Opens the next pass with a lit cell (planner.md "Passes"): its rows in row_, its head row, and its
// layout at the job's window (layout()), or as `kept` has it; false when there is none, or none yet
// (starved()).
bool ScanPlanner::collect(int32_t& hy, int32_t& first, int32_t& last, uint64_t& span, const KeptPass* kept, bool* restored) {
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
    hy = static_cast<int32_t>(r) - dyMin_;
    for (uint8_t k = 0; k < 4; k++) {
      row_[k] = -1;
      const int32_t rk = hy + h_.offsets[k][1];
      if (rk < 0 || rk >= h_.rows || covered(rk)) continue;
      cover(rk);
      row_[k] = static_cast<int16_t>(rk);
    }
    if (kept && kept->hy != hy) continue;  // planning found no lit cell here: dropped, as it was then
    const bool given = kept && restore(*kept, first, last, span);
    if (restored) *restored = given;
    if (!given) {
      pass_ = motion();  // the job's window first
      if (!layout(first, last, span)) continue;  // no lit cell: the pass is dropped
    }
    uncover(scan_);
    scan_++;
    return true;
  }
  return false;
}

// The pass on the rows in row_ as planning kept it: its motion, extent and flown stretches as
// layout() and the link cap found them, and its span, with no cell read. False when it is not one
// planning could have kept (the card's file is not what M29 wrote): the pass is then laid out.
bool ScanPlanner::restore(const KeptPass& k, int32_t& first, int32_t& last, uint64_t& span) {
  if (k.windowUs < motion().windowUs || k.first > k.last || switchSpan() * k.windowUs >= (1ull << 32)) return false;
  const int64_t columns = static_cast<int64_t>(k.last) - k.first + 1;
  if (k.first < -static_cast<int64_t>(switchSpan()) || columns > static_cast<int64_t>(switchSpan())) return false;
  uint8_t n = 0;
  while (n < kMaxJumps && k.jumpG[n]) {
    // Inside the pass, ascending, a lit window on each side of each stretch.
    const uint16_t from = n ? k.jumpCol[n - 1] + k.jumpG[n - 1] + 1 : 1;
    if (k.jumpCol[n] < from || static_cast<int64_t>(k.jumpCol[n]) + k.jumpG[n] >= columns) return false;
    n++;
  }
  pass_ = uv::passMotion(h_, m_, k.windowUs);
  flies_ = mayFly();
  first = first_ = k.first;
  last = k.last;
  for (jumpCount_ = 0; jumpCount_ < n; jumpCount_++) {
    jumpCol_[jumpCount_] = k.jumpCol[jumpCount_];
    jumpG_[jumpCount_] = k.jumpG[jumpCount_];
  }
  jumpNext_ = 0;
  return flownSpan(first, last, span);  // false: a stretch this pass would not fly
}

// The open pass laid out again at a window of w µs (longer than the job's), its cursors reopened;
// false when its switch times would outgrow 32 bits.
bool ScanPlanner::layOutAt(uint64_t w, int32_t& first, int32_t& last, uint64_t& span) {
  if (switchSpan() * w >= (1ull << 32)) {
    refusal_ = Refusal::TooLong;
    return false;
  }
  pass_ = uv::passMotion(h_, m_, static_cast<uint32_t>(w));
  layout(first, last, span);
  openPass();
  return true;
}

// The pass on the rows in row_, laid out at the job's window (or as kept: `found`), from where the
// head stands, link-capped and stroked, and in a mixed job priced as stops too; added to the
// estimate. False when the plan must end here.
bool ScanPlanner::planPass(int32_t hy, int32_t first, int32_t last, uint64_t span, ScanPass& out, bool found) {
  descending_ = passes_ % 2 == 1;
#ifndef __AVR__
  replay_ = false;  // the log is the pass before's
#endif
  start_ = descending_ ? last : first;
  openPass();
  // The link cap (planner.md "The printhead link"): a pass whose program lines would outrun the link
  // is laid out again at a longer window, until they fit. A kept pass is at the window this found.
  for (uint64_t need, have; !found && outrunsLink(need, have);) {
    uint64_t w = have ? ceilDiv(static_cast<uint64_t>(pass_.windowUs) * need, have) : 2ull * pass_.windowUs;
    if (w <= pass_.windowUs) w = pass_.windowUs + 1ull;
    if (!layOutAt(w, first, last, span)) return false;
  }
  const int32_t reach = static_cast<int32_t>((h_.pitchUm[0] + 1) / 2 + pass_.overscanUm);
  out.hy = hy;
  out.descending = descending_;
  out.first = first;
  out.last = last;
  out.runUpUm = descending_ ? X(last) + reach : X(first) - reach;
  out.runOutUm = descending_ ? X(first) - reach : X(last) + reach;
  out.stopsUs = 0;
  out.stops = false;
  out.band = 0;
  // The pass as the Mega runs it (planner.md "The stroke"): the step engine's move to the stroke's
  // start, the overhead, the stroke, and what confirming the pass outlasts its run-out (endUs).
  uint64_t q16;
  if (!engineStep(m_, h_.pitchUm[0], pass_.windowUs, q16)) {
    refusal_ = Refusal::Engine;  // the job's window, or a pass the link cap slowed, is beyond the step engine
    return false;
  }
  if (mode_ & kUnpriced && h_.strategy == Strategy::Scan) {
    out.moveUs = out.strokeUs = out.markUs = out.runOutUs = out.endUs = 0;
    out.startSteps = out.stopSteps = 0;
    out.scanUs = 0;
    passes_++;
    return true;
  }
  const int32_t pitch = static_cast<int32_t>(h_.pitchUm[0]), dir = descending_ ? -1 : 1;
  const int32_t x0 = X(descending_ ? last : first), x1 = X(descending_ ? first : last);
  const uint64_t saved = static_cast<uint64_t>(last - first + 1) * pass_.windowUs - span;
  planStroke(m_, 2 * x0 - dir * pitch, 2 * x1 + dir * pitch, descending_, q16, static_cast<uint32_t>(saved), out);
  const int32_t y = Y(out.hy), dy = axisSteps(m_, 1, y) - axisSteps(m_, 1, curY_), dx = out.startSteps - curX_;
  const uint32_t ady = static_cast<uint32_t>(dy < 0 ? -dy : dy);
  const uint32_t adx = static_cast<uint32_t>(dx < 0 ? -dx : dx);
  GlidePlan glide;
  if (runOut_ && planGlide(ady, axisRate(m_, 1), axisAccel(m_, 1), glide)) {
    // After a stroke, the hop in Y glides (planner.md "Gliding") from the time that pass is
    // confirmed, beside its run-out and the X move queued after it: the pass pays what the later of
    // the two ends past the last pass's rest and confirmation.
    const uint32_t g = (glide.ticks + 1) / 2, x = engineMoveUs(m_, adx, 0);
    const uint32_t rest = runOut_ > kScanPassEndUs ? runOut_ : kScanPassEndUs;
    out.moveUs = kScanPassEndUs + g > rest + x ? kScanPassEndUs + g - rest : x;
  } else {
    out.moveUs = engineMoveUs(m_, adx, ady);
  }
  out.scanUs = static_cast<uint64_t>(out.moveUs) + kScanPassLoadUs + out.strokeUs + out.endUs;
  int32_t endX = out.stopSteps;
  if (h_.strategy == Strategy::Mixed) {  // planner.md "Mixed mode": the stops when they cost no more than the stroke
    out.stopsUs = priceStops(out.hy, endX);
    out.stops = out.stopsUs <= out.scanUs;
    openPass();  // the cursors again, for the events or the stops
    setStopPass(out.stops);
  }
  estimate_ += out.stops ? out.stopsUs : out.scanUs;
  curX_ = out.stops ? endX : out.stopSteps;
  curY_ = y;
  runOut_ = static_cast<uint16_t>(out.stops ? 0 : out.runOutUs > 65535 ? 65535 : out.runOutUs);
  passes_++;
  return true;
}

}  // namespace uv
