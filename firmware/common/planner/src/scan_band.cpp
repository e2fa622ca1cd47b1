// A mixed job's bands in the scan planner (protocol/planner.md "Bands"): kMixedBand passes priced pass
// by pass and as one group of stops column by column, taken the cheaper way; the band's stops one at a
// time, each pass reopened where its last stop left it, so the four cursors of a pass are enough.
#include "scan.h"

namespace uv {

namespace {
int32_t absDiff(int32_t a, int32_t b) { return a > b ? a - b : b - a; }
}  // namespace

bool ScanPlanner::nextBand(ScanPass& out) {
  if (bandNext_ != kFilling && bandNext_ == bandLen_) {  // the band before is done
    bandLen_ = 0;
    bandNext_ = kFilling;
    bandLeds_ = 0;
  }
  if (bandNext_ == kFilling) {
    if (bandPriced_ == 0) {
      // Gathered until it has kMixedBand passes or the job has no more; a band part gathered stays
      // so while rows are awaited, its rows taken (as `shortest`'s).
      for (int32_t hy, first, last; bandLen_ < kMixedBand;) {
        uint64_t span;
        if (!collect(hy, first, last, span)) break;
        bandHy_[bandLen_] = static_cast<int16_t>(hy);
        for (uint8_t k = 0; k < 4; k++)
          if (row_[k] >= 0) bandLeds_ |= 1ul << (4 * bandLen_ + k);
        bandLen_++;
      }
      if (starved_ || bandLen_ == 0) return false;
      bandX0_ = curX_;
      bandY0_ = curY_;
      bandRunOut0_ = runOut_;
      bandUs_ = 0;
    }
    // The band pass by pass, each from where the one before leaves the head; undone once priced.
    while (bandPriced_ < bandLen_) {
      int32_t first, last;
      uint64_t span;
      bandRows(bandPriced_);
      pass_ = motion();
      layout(first, last, span);
      if (!planPass(bandHy_[bandPriced_], first, last, span, out)) return false;
      live_ = static_cast<uint8_t>(live_ & ~kStopPassBit);  // priced, not open
      bandUs_ += out.stops ? out.stopsUs : out.scanUs;
      if (++bandPriced_ < bandLen_ && (live_ & kSlicedBit)) return false;  // pricing()
    }
    const uint64_t passesUs = bandUs_;
    curX_ = bandX0_;
    curY_ = bandY0_;
    runOut_ = bandRunOut0_;
    estimate_ -= passesUs;
    passes_ = static_cast<uint16_t>(passes_ - bandLen_);
    bandPriced_ = 0;
    int32_t endX, endY;
    const uint64_t bandUs = priceBand(passesUs, endX, endY);
    if (bandUs < passesUs) {  // strictly cheaper: else pass by pass, as `shortest` takes its columns
      int32_t first, last;
      openBand(first, last);
      out = ScanPass{};
      out.hy = bandHy_[0];
      out.descending = descending_;
      out.first = first;
      out.last = last;
      out.scanUs = passesUs;
      out.stopsUs = bandUs;
      out.stops = true;
      out.band = bandLen_;
      estimate_ += bandUs;
      passes_ = static_cast<uint16_t>(passes_ + bandLen_);
      curX_ = endX;
      curY_ = endY;
      runOut_ = 0;  // the band's stops end at rest
      bandNext_ = bandLen_;
      live_ |= kStopPassBit | kBandBit;
      return true;
    }
    bandNext_ = 0;
  }
  int32_t first, last;
  uint64_t span;
  bandRows(bandNext_);
  pass_ = motion();
  layout(first, last, span);
  return planPass(bandHy_[bandNext_++], first, last, span, out);
}

// row_ for the band's pass q.
void ScanPlanner::bandRows(uint8_t q) {
  for (uint8_t k = 0; k < 4; k++)
    row_[k] = bandLeds_ >> (4 * q + k) & 1 ? static_cast<int16_t>(bandHy_[q] + h_.offsets[k][1]) : -1;
}

// Opens pass q's cursors at head column `from` in descending_'s direction: the head column of its
// first stop there or beyond, or kNoColumn. Each LED's first lit cell waits in hx_ and us_.
int32_t ScanPlanner::bandPeek(uint8_t q, int32_t from) {
  bandRows(q);
  bool any = false;
  int32_t best = kNoColumn;
  for (uint8_t k = 0; k < 4; k++) {
    setLive(k, false);
    if (row_[k] < 0) continue;
    int32_t c = from + h_.offsets[k][0];
    if (descending_ ? c < 0 : c >= static_cast<int32_t>(h_.cols)) continue;  // nothing that way
    if (c < 0) c = 0;
    if (c >= static_cast<int32_t>(h_.cols)) c = h_.cols - 1;
    cells_.openAt(k, static_cast<uint16_t>(row_[k]), descending_, static_cast<uint16_t>(c));
    peek(k);
    if (isLive(k) && (!any || (descending_ ? hx_[k] > best : hx_[k] < best))) {
      best = hx_[k];
      any = true;
    }
  }
  return best;
}

// Sets the band's stops going from where the head stands: its extent, the columns' direction
// (descending_: ascending unless the extent's far end is nearer the head's X), each pass's first stop.
void ScanPlanner::openBand(int32_t& first, int32_t& last) {
  first = INT32_MAX;
  last = INT32_MIN;
  for (uint8_t q = 0; q < bandLen_; q++) {
    descending_ = false;
    const int32_t lo = bandPeek(q, INT16_MIN);
    descending_ = true;
    const int32_t hi = bandPeek(q, INT16_MAX);
    if (lo < first) first = lo;
    if (hi > last) last = hi;
  }
  descending_ = absDiff(axisSteps(m_, 0, X(first)), curX_) > absDiff(axisSteps(m_, 0, X(last)), curX_);
  for (uint8_t q = 0; q < bandLen_; q++)
    u_.band.nextHx[q] = static_cast<int16_t>(bandPeek(q, descending_ ? INT16_MAX : INT16_MIN));
  u_.band.colHx = kNoColumn;
  u_.band.startY = curY_;
  u_.band.lastQ = 0xff;
}

// The band's stops from where the head stands: their time, and where the last leaves the head (X in
// steps, Y in µm). Only whether it is below `limit` matters once it reaches it: a dense band, every
// cell a stop, is left there (on the Mega, walking all its stops would hold the main loop long).
uint64_t ScanPlanner::priceBand(uint64_t limit, int32_t& endX, int32_t& endY) {
  int32_t first, last;
  openBand(first, last);
  int32_t x = curX_, y = axisSteps(m_, 1, curY_);
  endY = curY_;
  uint64_t total = 0;
  Stop s;
  while (bandNextStop(s)) {
    const int32_t to = axisSteps(m_, 0, X(s.hx)), toY = axisSteps(m_, 1, Y(s.hy));
    total += stopCostStepsUs(m_, to - x, toY - y, s.us);
    x = to;
    y = toY;
    endY = Y(s.hy);
    if (total >= limit) break;
  }
  endX = x;
  return total;
}

// The band's next stop: column by column in descending_'s direction, each column's passes in head row
// order from the end nearer the head's Y (ties: ascending). False at the band's end.
bool ScanPlanner::bandNextStop(Stop& out) {
  for (;;) {
    if (u_.band.colHx == kNoColumn) {  // the next column
      int32_t best = kNoColumn;
      uint8_t lo = 0xff, hi = 0;
      for (uint8_t q = 0; q < bandLen_; q++) {
        const int32_t h = u_.band.nextHx[q];
        if (h == kNoColumn) continue;
        if (best == kNoColumn || (descending_ ? h > best : h < best)) best = h;
      }
      if (best == kNoColumn) {
        live_ = static_cast<uint8_t>(live_ & ~(kStopPassBit | kBandBit));
        return false;
      }
      for (uint8_t q = 0; q < bandLen_; q++)
        if (u_.band.nextHx[q] == best) {
          if (lo == 0xff) lo = q;
          hi = q;
        }
      const int32_t y = u_.band.lastQ == 0xff ? u_.band.startY : Y(bandHy_[u_.band.lastQ]);
      const bool up = absDiff(Y(bandHy_[lo]), y) > absDiff(Y(bandHy_[hi]), y);
      live_ = static_cast<uint8_t>(up ? live_ | kColumnUpBit : live_ & ~kColumnUpBit);
      u_.band.colHx = static_cast<int16_t>(best);
    }
    const bool up = live_ & kColumnUpBit;
    uint8_t q = 0xff;
    for (uint8_t i = 0; i < bandLen_; i++) {
      const uint8_t p = up ? static_cast<uint8_t>(bandLen_ - 1 - i) : i;
      if (u_.band.nextHx[p] == u_.band.colHx) {
        q = p;
        break;
      }
    }
    if (q == 0xff) {
      u_.band.colHx = kNoColumn;
      continue;
    }
    const int32_t hx = u_.band.colHx;
    bandPeek(q, hx);
    out.hx = hx;
    out.hy = bandHy_[q];
    for (uint8_t k = 0; k < 4; k++) {
      out.us[k] = 0;
      if (!isLive(k) || hx_[k] != hx) continue;
      out.us[k] = us_[k];
      peek(k);
    }
    int32_t next = kNoColumn;
    for (uint8_t k = 0; k < 4; k++)
      if (isLive(k) && (next == kNoColumn || (descending_ ? hx_[k] > next : hx_[k] < next))) next = hx_[k];
    u_.band.nextHx[q] = static_cast<int16_t>(next);
    u_.band.lastQ = q;
    return true;
  }
}

}  // namespace uv
