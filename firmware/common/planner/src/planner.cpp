// The exposure planner (protocol/planner.md): streams a job's stops one at a time from a CellSource.
#include "planner.h"

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

inline int32_t absDiff(int32_t a, int32_t b) { return a > b ? a - b : b - a; }

}  // namespace

Durations::Durations(const JobHeader& h) : linear_(h.map == DoseMap::Linear), level_(h.level) {
  for (uint8_t k = 0; k < 4; k++) {
    uint64_t full = h.byTarget ? roundDiv(static_cast<uint64_t>(h.targetUJcm2) * 1000000u, h.irradianceUWcm2[k]) : h.fullUs;
    scale_[k] = full * h.gainPermille[k];
  }
}

uint32_t Durations::us(uint8_t led, uint8_t value) const {
  uint32_t m = linear_ ? value : (value >= level_ && value > 0 ? 255 : 0);
  if (m == 0) return 0;
  return static_cast<uint32_t>(roundDiv(scale_[led] * m, 255000));
}

uint32_t Durations::longest(const uint8_t value[4]) const {
  uint32_t best = 0;
  for (uint8_t k = 0; k < 4; k++) {
    uint32_t t = us(k, value[k]);
    if (t > best) best = t;
  }
  return best;
}

Planner::Planner(const JobHeader& h, CellSource& cells, const Machine& m)
    : h_(h), cells_(cells), m_(m), dose_(h), curX_(m.startUm[0]), curY_(m.startUm[1]), rng_(h.seed ? h.seed : 0x9E3779B9u) {
  dyMin_ = h.offsets[0][1];
  for (uint8_t k = 1; k < 4; k++)
    if (h.offsets[k][1] < dyMin_) dyMin_ = h.offsets[k][1];
}

// --- passes ---------------------------------------------------------------------------------

bool Planner::openPass(PassInfo& p) {
  for (; scan_ < h_.rows; scan_++) {
    uint16_t r = scan_;
    if (covered_[r >> 3] & (1 << (r & 7))) continue;
    if (!cells_.rowNonEmpty(r)) continue;
    p.hy = static_cast<int32_t>(r) - dyMin_;
    p.first = INT32_MAX;
    p.last = INT32_MIN;
    p.cells = false;
    p.lit = true;
    for (uint8_t k = 0; k < 4; k++) {
      p.row[k] = -1;
      int32_t rk = p.hy + h_.offsets[k][1];
      if (rk < 0 || rk >= h_.rows || (covered_[rk >> 3] & (1 << (rk & 7)))) continue;
      covered_[rk >> 3] |= static_cast<uint8_t>(1 << (rk & 7));
      uint16_t lo, hi;
      if (!cells_.rowExtent(static_cast<uint16_t>(rk), lo, hi)) continue;  // an empty row: the LED idles
      p.row[k] = static_cast<int16_t>(rk);
      int32_t dx = h_.offsets[k][0];
      if (lo - dx < p.first) p.first = lo - dx;
      if (hi - dx > p.last) p.last = hi - dx;
      p.cells = true;
    }
    scan_++;
    return true;
  }
  return false;
}

void Planner::openCursors(uint8_t q, bool descending) {
  for (uint8_t k = 0; k < 4; k++) {
    uint8_t c = static_cast<uint8_t>(q * 4 + k);
    live_[c] = band_[q].row[k] >= 0;
    if (!live_[c]) continue;
    cells_.open(c, static_cast<uint16_t>(band_[q].row[k]), descending);
    advance(c);
  }
}

void Planner::advance(uint8_t c) { live_[c] = cells_.next(c, col_[c], val_[c]); }

// The pass's next stop in its direction that has light: its LEDs' cursors merged by head column.
bool Planner::passNext(uint8_t q, bool descending, int32_t& hx, uint8_t value[4]) {
  for (;;) {
    bool any = false;
    int32_t best = 0;
    for (uint8_t k = 0; k < 4; k++) {
      uint8_t c = static_cast<uint8_t>(q * 4 + k);
      if (!live_[c]) continue;
      int32_t h = static_cast<int32_t>(col_[c]) - h_.offsets[k][0];
      if (!any || (descending ? h > best : h < best)) best = h;
      any = true;
    }
    if (!any) return false;
    bool lit = false;
    for (uint8_t k = 0; k < 4; k++) {
      uint8_t c = static_cast<uint8_t>(q * 4 + k);
      value[k] = 0;
      if (live_[c] && static_cast<int32_t>(col_[c]) - h_.offsets[k][0] == best) {
        value[k] = val_[c];
        if (dose_.us(k, val_[c]) > 0) lit = true;
        advance(c);
      }
    }
    if (lit) {
      hx = best;
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
    int32_t hx;
    uint8_t v[4];
    while (passNext(q, desc, hx, v)) {
      total += stopCostUs(m_, x, y, X(hx), Y(p.hy), dose_.longest(v));
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
    if (!peek_[q]) continue;
    if (!any || (desc_ ? peekStop_[q].hx > best : peekStop_[q].hx < best)) best = peekStop_[q].hx;
    any = true;
  }
  if (!any) return false;
  columnLen_ = columnPos_ = 0;
  for (uint8_t q = 0; q < bandLen_; q++) {  // passes are in ascending hy
    if (!peek_[q] || peekStop_[q].hx != best) continue;
    column_[columnLen_] = q;
    columnStop_[columnLen_++] = peekStop_[q];
    peek_[q] = passNext(q, desc_, peekStop_[q].hx, peekStop_[q].value);
  }
  int32_t yFirst = Y(band_[column_[0]].hy), yLast = Y(band_[column_[columnLen_ - 1]].hy);
  if (absDiff(yFirst, curY_) > absDiff(yLast, curY_)) {
    for (uint8_t i = 0, j = static_cast<uint8_t>(columnLen_ - 1); i < j; i++, j--) {
      uint8_t tq = column_[i];
      column_[i] = column_[j];
      column_[j] = tq;
      Compact ts = columnStop_[i];
      columnStop_[i] = columnStop_[j];
      columnStop_[j] = ts;
    }
  }
  return true;
}

// Opens every pass of the band with stops for the Columns order and reads each one's first stop.
void Planner::openColumns() {
  desc_ = columnsDescending(curX_);
  for (uint8_t q = 0; q < bandLen_; q++) {
    peek_[q] = false;
    if (!band_[q].lit) continue;
    openCursors(q, desc_);
    peek_[q] = passNext(q, desc_, peekStop_[q].hx, peekStop_[q].value);
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
      int32_t x = X(columnStop_[i].hx), y = Y(band_[column_[i]].hy);
      total += stopCostUs(m_, curX_, curY_, x, y, dose_.longest(columnStop_[i].value));
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
    bandLen_ = 0;
    uint8_t want = h_.strategy == Strategy::Shortest ? kShortestBand : 1;
    while (bandLen_ < want && openPass(band_[bandLen_])) bandLen_++;
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
  for (;;) {
    if (!emitting_ && !startBand()) return false;
    if (order_ == Order::Columns) {
      if (columnPos_ == columnLen_ && !nextColumn()) {
        emitting_ = false;
        continue;
      }
      uint8_t q = column_[columnPos_];
      const Compact& c = columnStop_[columnPos_++];
      if (!passUsed_[q]) {
        passUsed_[q] = true;
        passes_++;
      }
      emit(c.hx, band_[q].hy, c.value, out);
      return true;
    }
    bool got = false;
    int32_t hx = 0;
    uint8_t value[4];
    if (h_.strategy == Strategy::Random) {
      if (blockPos_ == blockLen_) {
        blockLen_ = blockPos_ = 0;
        while (blockLen_ < kRandomBlock && passNext(q_, false, block_[blockLen_].hx, block_[blockLen_].value)) blockLen_++;
        for (uint8_t i = blockLen_ > 0 ? static_cast<uint8_t>(blockLen_ - 1) : 0; i >= 1; i--) {
          uint8_t j = static_cast<uint8_t>(xorshift32(rng_) % (i + 1u));
          Compact t = block_[i];
          block_[i] = block_[j];
          block_[j] = t;
        }
      }
      if (blockPos_ < blockLen_) {
        hx = block_[blockPos_].hx;
        for (uint8_t k = 0; k < 4; k++) value[k] = block_[blockPos_].value[k];
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
