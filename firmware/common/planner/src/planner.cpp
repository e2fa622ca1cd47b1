// The exposure planner (protocol/planner.md): streams a job's stops one at a time from a CellSource.
#include "planner.h"

#include <string.h>

namespace uv {

namespace {

// round(n / d), half up.
uint64_t roundDiv(uint64_t n, uint64_t d) {
  uint64_t q = n / d;
  return (n - q * d) * 2 >= d ? q + 1 : q;
}

uint32_t xorshift32(uint32_t& x) {
  x ^= x << 13;
  x ^= x >> 17;
  x ^= x << 5;
  return x;
}

// round(n / 255000) for n < 255 × 255000 + 127500: eight compare-and-subtracts, a quotient's bits
// from the top (the AVR's 32-bit division takes 36 µs; this, a few).
uint8_t roundDivBy255000(uint32_t n) {
  n += 127500;
  uint32_t d = 255000ul << 7;
  uint8_t q = 0;
  for (uint8_t bit = 0x80; bit; bit >>= 1, d >>= 1)
    if (n >= d) {
      n -= d;
      q |= bit;
    }
  return q;
}

inline int32_t absDiff(int32_t a, int32_t b) { return a > b ? a - b : b - a; }

}  // namespace

Durations::Durations(const JobHeader& h) : linear_(h.map == DoseMap::Linear), level_(h.level) {
  for (uint8_t k = 0; k < 4; k++) {
    uint64_t full = h.byTarget ? roundDiv(static_cast<uint64_t>(h.targetUJcm2) * 1000000u, h.irradianceUWcm2[k]) : h.fullUs;
    const uint64_t scale = full * h.gainPermille[k];
    whole_[k] = static_cast<uint32_t>(scale / 255000);
    part_[k] = static_cast<uint32_t>(scale % 255000);
  }
#ifndef __AVR__
  for (uint8_t k = 0; k < 4; k++)
    for (uint16_t v = 0; v < 256; v++) table_[k][v] = compute(k, static_cast<uint8_t>(v));
#endif
}

// On the AVR, a cell's duration worked out when asked; elsewhere, once a value for the table.
#ifdef __AVR__
uint32_t Durations::us(uint8_t led, uint8_t value) const {
#else
uint32_t Durations::compute(uint8_t led, uint8_t value) const {
#endif
  uint32_t m = linear_ ? value : (value >= level_ && value > 0 ? 255 : 0);
  if (m == 0) return 0;
  // round(scale × m / 255000) = whole × m + round(part × m / 255000), modulo 2³² as ever.
  return whole_[led] * m + roundDivBy255000(part_[led] * m);
}

uint32_t Durations::longest(const uint8_t value[4]) const {
  uint32_t best = 0;
  for (uint8_t k = 0; k < 4; k++) {
    uint32_t t = us(k, value[k]);
    if (t > best) best = t;
  }
  return best;
}

Planner::Planner(const JobHeader& h, CellSource& cells, const MotionModel& m)
    : h_(h), cells_(cells), m_(m), dose_(h), known_(h.rows), curX_(m.startUm[0]), curY_(m.startUm[1]), rng_(h.seed ? h.seed : 0x9E3779B9u) {
  memset(&shared_, 0, sizeof shared_);  // no pass has a stop peeked yet
  dyMin_ = dyMax_ = h.offsets[0][1];
  for (uint8_t k = 1; k < 4; k++) {
    if (h.offsets[k][1] < dyMin_) dyMin_ = h.offsets[k][1];
    if (h.offsets[k][1] > dyMax_) dyMax_ = h.offsets[k][1];
  }
}

// --- passes ---------------------------------------------------------------------------------

void Planner::uncoverBelow(uint16_t row) {
  // Rows below the lowest open row are never read again: their ring slots become the rows a
  // window above it.
  covered_[(row & (kCoveredWindowRows - 1)) >> 3] &= static_cast<uint8_t>(~(1 << (row & 7)));
}

Planner::Open Planner::openPass(PassInfo& p) {
  for (; scan_ < h_.rows; uncoverBelow(scan_), scan_++) {
    uint16_t r = scan_;
    if (r >= known_) return Open::NeedRows;
    if (covered(r)) continue;
    if (!cells_.rowNonEmpty(r)) continue;
    // A pass is settled once the last row any of its LEDs reads has arrived.
    int32_t top = static_cast<int32_t>(r) - dyMin_ + dyMax_;
    if (top > h_.rows - 1) top = h_.rows - 1;
    if (known_ < h_.rows && top >= known_) return Open::NeedRows;
    p.hy = static_cast<Head>(r - dyMin_);
    p.first = INT16_MAX;
    p.last = INT16_MIN;
    p.cells = false;
    p.lit = true;
    for (uint8_t k = 0; k < 4; k++) {
      p.row[k] = -1;
      int32_t rk = p.hy + h_.offsets[k][1];
      if (rk < 0 || rk >= h_.rows || covered(rk)) continue;
      cover(rk);
      uint16_t lo, hi;
      if (!cells_.rowExtent(static_cast<uint16_t>(rk), lo, hi)) continue;  // an empty row: the LED idles
      p.row[k] = static_cast<int16_t>(rk);
      int32_t dx = h_.offsets[k][0];
      if (lo - dx < p.first) p.first = static_cast<Head>(lo - dx);
      if (hi - dx > p.last) p.last = static_cast<Head>(hi - dx);
      p.cells = true;
    }
    uncoverBelow(scan_);
    scan_++;
    return Open::Opened;
  }
  return Open::NoMore;
}

int32_t Planner::lowestRowNeeded() const {
  // The band being emitted (or filled) reads from its first pass's lowest LED row; passes still to
  // open read from the lowest open row up.
  int32_t low = scan_;
  for (uint8_t q = 0; q < bandLen_; q++) {
    int32_t r = band_[q].hy + dyMin_;
    if (r < low) low = r;
  }
  return low < 0 ? 0 : low;
}

void Planner::openCursors(uint8_t q, bool descending) {
  for (uint8_t k = 0; k < 4; k++)
    if (band_[q].row[k] >= 0) cells_.open(static_cast<uint8_t>(q * 4 + k), static_cast<uint16_t>(band_[q].row[k]), descending);
}

// The pass's next stop in its direction that has light: its LEDs' cursors merged by head column.
// A cursor of an LED with no row in the pass was not opened: its cell is not looked at.
bool Planner::passNext(uint8_t q, bool descending, Head& hx, uint8_t value[4]) {
  for (;;) {
    bool any = false;
    int32_t best = 0;
    for (uint8_t k = 0; k < 4; k++) {
      uint16_t col;
      uint8_t v;
      if (band_[q].row[k] < 0 || !cells_.at(static_cast<uint8_t>(q * 4 + k), col, v)) continue;
      int32_t h = static_cast<int32_t>(col) - h_.offsets[k][0];
      if (!any || (descending ? h > best : h < best)) best = h;
      any = true;
    }
    if (!any) return false;
    bool lit = false;
    for (uint8_t k = 0; k < 4; k++) {
      uint8_t c = static_cast<uint8_t>(q * 4 + k);
      uint16_t col;
      uint8_t v;
      value[k] = 0;
      if (band_[q].row[k] >= 0 && cells_.at(c, col, v) && static_cast<int32_t>(col) - h_.offsets[k][0] == best) {
        value[k] = v;
        if (dose_.us(k, v) > 0) lit = true;
        cells_.step(c);
      }
    }
    if (lit) {
      hx = static_cast<Head>(best);
      return true;
    }
  }
}

bool Planner::descendingFor(const PassInfo& p, int32_t x) const { return absDiff(X(p.first), x) > absDiff(X(p.last), x); }

// --- pricing the two band orders of `shortest` ---------------------------------------------------

uint64_t Planner::priceRows() {
  uint64_t total = 0;
  int32_t x = curX_, y = curY_;
  for (uint8_t q = 0; q < bandLen_; q++) {
    PassInfo& p = band_[q];
    p.lit = false;
    if (!p.cells) continue;
    bool desc = descendingFor(p, x);
    openCursors(q, desc);
    Head hx;
    uint8_t v[4];
    while (passNext(q, desc, hx, v)) {
      uint32_t us[4];
      dose_.each(v, us);
      total += stopCostUs(m_, x, y, X(hx), Y(p.hy), us);
      x = X(hx);
      y = Y(p.hy);
      p.lit = true;
    }
  }
  return total;
}

bool Planner::columnsDescending(int32_t x) const {
  int32_t first = INT32_MAX, last = INT32_MIN;
  for (uint8_t q = 0; q < bandLen_; q++) {
    if (!band_[q].lit) continue;
    if (band_[q].first < first) first = band_[q].first;
    if (band_[q].last > last) last = band_[q].last;
  }
  return absDiff(X(first), x) > absDiff(X(last), x);
}

// Builds the next column of the Columns order from the passes' next stops; false at the band's end.
bool Planner::nextColumn() {
  bool any = false;
  int32_t best = 0;
  for (uint8_t q = 0; q < bandLen_; q++) {
    if (!shared_.col.peek_[q]) continue;
    if (!any || (desc_ ? shared_.col.peekStop_[q].hx > best : shared_.col.peekStop_[q].hx < best)) best = shared_.col.peekStop_[q].hx;
    any = true;
  }
  if (!any) return false;
  columnLen_ = columnPos_ = 0;
  for (uint8_t q = 0; q < bandLen_; q++) {  // passes are in ascending hy
    if (!shared_.col.peek_[q] || shared_.col.peekStop_[q].hx != best) continue;
    shared_.col.column_[columnLen_] = q;
    shared_.col.columnStop_[columnLen_++] = shared_.col.peekStop_[q];
    shared_.col.peek_[q] = passNext(q, desc_, shared_.col.peekStop_[q].hx, shared_.col.peekStop_[q].value);
  }
  int32_t yFirst = Y(band_[shared_.col.column_[0]].hy), yLast = Y(band_[shared_.col.column_[columnLen_ - 1]].hy);
  if (absDiff(yFirst, curY_) > absDiff(yLast, curY_)) {
    for (uint8_t i = 0, j = static_cast<uint8_t>(columnLen_ - 1); i < j; i++, j--) {
      uint8_t tq = shared_.col.column_[i];
      shared_.col.column_[i] = shared_.col.column_[j];
      shared_.col.column_[j] = tq;
      Compact ts = shared_.col.columnStop_[i];
      shared_.col.columnStop_[i] = shared_.col.columnStop_[j];
      shared_.col.columnStop_[j] = ts;
    }
  }
  return true;
}

// Opens every pass of the band with stops for the Columns order and reads each one's first stop.
void Planner::openColumns() {
  desc_ = columnsDescending(curX_);
  for (uint8_t q = 0; q < bandLen_; q++) {
    shared_.col.peek_[q] = false;
    if (!band_[q].lit) continue;
    openCursors(q, desc_);
    shared_.col.peek_[q] = passNext(q, desc_, shared_.col.peekStop_[q].hx, shared_.col.peekStop_[q].value);
  }
  columnLen_ = columnPos_ = 0;
}

uint64_t Planner::priceColumns() {
  // Simulated with the emission machinery itself, then undone: the head position is restored.
  int32_t x0 = curX_, y0 = curY_;
  openColumns();
  uint64_t total = 0;
  while (nextColumn()) {
    for (uint8_t i = 0; i < columnLen_; i++) {
      int32_t x = X(shared_.col.columnStop_[i].hx), y = Y(band_[shared_.col.column_[i]].hy);
      uint32_t us[4];
      dose_.each(shared_.col.columnStop_[i].value, us);
      total += stopCostUs(m_, curX_, curY_, x, y, us);
      curX_ = x;
      curY_ = y;
    }
  }
  curX_ = x0;
  curY_ = y0;
  return total;
}

// --- emission ---------------------------------------------------------------------------------

bool Planner::startBand() {
  for (;;) {
    if (!filling_) bandLen_ = 0;
    filling_ = true;
    uint8_t want = h_.strategy == Strategy::Shortest ? kShortestBand : 1;
    Open o = Open::Opened;
    while (bandLen_ < want && (o = openPass(band_[bandLen_])) == Open::Opened) bandLen_++;
    if (o == Open::NeedRows) {  // a row yet to come may still open a pass in this band
      starved_ = true;
      return false;
    }
    filling_ = false;
    if (bandLen_ == 0) return false;
    for (uint8_t q = 0; q < bandLen_; q++) passUsed_[q] = false;
    order_ = Order::Rows;
    if (h_.strategy == Strategy::Shortest) {
      uint64_t rows = priceRows();
      bool anyLit = false;
      for (uint8_t q = 0; q < bandLen_; q++) anyLit = anyLit || band_[q].lit;
      if (!anyLit) continue;
      if (priceColumns() < rows) order_ = Order::Columns;
    }
    if (order_ == Order::Columns) {
      openColumns();
    } else {
      q_ = 0;
      if (!startRowPass()) continue;
    }
    emitting_ = true;
    return true;
  }
}

// Opens pass q_ (or the next one with cells) for the Rows order; false when the band is done.
bool Planner::startRowPass() {
  for (; q_ < bandLen_; q_++) {
    const PassInfo& p = band_[q_];
    if (!p.cells || !p.lit) continue;
    switch (h_.strategy) {
      case Strategy::Serpentine: desc_ = passes_ % 2 == 1; break;
      case Strategy::Shortest: desc_ = descendingFor(p, curX_); break;
      default: desc_ = false;
    }
    openCursors(q_, desc_);
    blockLen_ = blockPos_ = 0;
    return true;
  }
  return false;
}

void Planner::emit(int32_t hx, int32_t hy, const uint8_t value[4], Stop& out) {
  out.hx = hx;
  out.hy = hy;
  for (uint8_t k = 0; k < 4; k++) out.us[k] = dose_.us(k, value[k]);
  curX_ = X(hx);
  curY_ = Y(hy);
}

bool Planner::next(Stop& out) {
  starved_ = false;
  if (!supported()) return false;
  for (;;) {
    if (!emitting_ && !startBand()) return false;
    if (order_ == Order::Columns) {
      if (columnPos_ == columnLen_ && !nextColumn()) {
        emitting_ = false;
        continue;
      }
      uint8_t q = shared_.col.column_[columnPos_];
      const Compact& c = shared_.col.columnStop_[columnPos_++];
      if (!passUsed_[q]) {
        passUsed_[q] = true;
        passes_++;
      }
      emit(c.hx, band_[q].hy, c.value, out);
      return true;
    }
    bool got = false;
    Head hx = 0;
    uint8_t value[4];
    if (h_.strategy == Strategy::Random) {
      if (blockPos_ == blockLen_) {
        blockLen_ = blockPos_ = 0;
        while (blockLen_ < kRandomBlock && passNext(q_, false, shared_.block_[blockLen_].hx, shared_.block_[blockLen_].value)) blockLen_++;
        for (uint8_t i = blockLen_ > 0 ? static_cast<uint8_t>(blockLen_ - 1) : 0; i >= 1; i--) {
          uint8_t j = static_cast<uint8_t>(xorshift32(rng_) % (i + 1u));
          Compact t = shared_.block_[i];
          shared_.block_[i] = shared_.block_[j];
          shared_.block_[j] = t;
        }
      }
      if (blockPos_ < blockLen_) {
        hx = shared_.block_[blockPos_].hx;
        for (uint8_t k = 0; k < 4; k++) value[k] = shared_.block_[blockPos_].value[k];
        blockPos_++;
        got = true;
      }
    } else {
      got = passNext(q_, desc_, hx, value);
    }
    if (got) {
      if (!passUsed_[q_]) {
        passUsed_[q_] = true;
        passes_++;
      }
      emit(hx, band_[q_].hy, value, out);
      return true;
    }
    q_++;
    if (!startRowPass()) emitting_ = false;
  }
}

}  // namespace uv
