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

Planner::Planner(const JobHeader& h, CellSource& cells, int32_t startXUm)
    : h_(h), cells_(cells), dose_(h), curX_(startXUm), rng_(h.seed ? h.seed : 0x9E3779B9u) {
  dyMin_ = h.offsets[0][1];
  for (uint8_t k = 1; k < 4; k++)
    if (h.offsets[k][1] < dyMin_) dyMin_ = h.offsets[k][1];
}

bool Planner::openPass() {
  for (; scan_ < h_.rows; scan_++) {
    uint16_t r = scan_;
    if (covered_[r >> 3] & (1 << (r & 7))) continue;
    if (!cells_.rowNonEmpty(r)) continue;
    hy_ = static_cast<int32_t>(r) - dyMin_;
    int32_t first = INT32_MAX, last = INT32_MIN;
    for (uint8_t k = 0; k < 4; k++) {
      live_[k] = false;
      int32_t rk = hy_ + h_.offsets[k][1];
      if (rk < 0 || rk >= h_.rows || (covered_[rk >> 3] & (1 << (rk & 7)))) continue;
      covered_[rk >> 3] |= static_cast<uint8_t>(1 << (rk & 7));
      uint16_t lo, hi;
      if (!cells_.rowExtent(static_cast<uint16_t>(rk), lo, hi)) continue;
      int32_t dx = h_.offsets[k][0];
      if (lo - dx < first) first = lo - dx;
      if (hi - dx > last) last = hi - dx;
      live_[k] = true;  // opened below, once the direction is known
    }
    switch (h_.strategy) {
      case Strategy::Serpentine: descending_ = passes_ % 2 == 1; break;
      case Strategy::Shortest: {
        int32_t xf = static_cast<int32_t>(h_.originUm[0]) + first * static_cast<int32_t>(h_.pitchUm[0]);
        int32_t xl = static_cast<int32_t>(h_.originUm[0]) + last * static_cast<int32_t>(h_.pitchUm[0]);
        descending_ = absDiff(xf, curX_) > absDiff(xl, curX_);
        break;
      }
      default: descending_ = false;
    }
    for (uint8_t k = 0; k < 4; k++) {
      if (!live_[k]) continue;
      cells_.open(k, static_cast<uint16_t>(hy_ + h_.offsets[k][1]), descending_);
      advance(k);
    }
    inPass_ = true;
    passEmitted_ = false;
    blockLen_ = blockPos_ = 0;
    scan_++;
    return true;
  }
  return false;
}

void Planner::advance(uint8_t k) { live_[k] = cells_.next(k, col_[k], val_[k]); }

bool Planner::mergeNext(int32_t& hx, uint8_t value[4]) {
  for (;;) {
    bool any = false;
    int32_t best = 0;
    for (uint8_t k = 0; k < 4; k++) {
      if (!live_[k]) continue;
      int32_t c = static_cast<int32_t>(col_[k]) - h_.offsets[k][0];
      if (!any || (descending_ ? c > best : c < best)) best = c;
      any = true;
    }
    if (!any) return false;
    bool lit = false;
    for (uint8_t k = 0; k < 4; k++) {
      value[k] = 0;
      if (live_[k] && static_cast<int32_t>(col_[k]) - h_.offsets[k][0] == best) {
        value[k] = val_[k];
        if (dose_.us(k, val_[k]) > 0) lit = true;
        advance(k);
      }
    }
    if (lit) {
      hx = best;
      return true;
    }
  }
}

void Planner::fillBlock() {
  blockLen_ = blockPos_ = 0;
  int32_t hx;
  while (blockLen_ < kRandomBlock && mergeNext(hx, block_[blockLen_].value)) {
    block_[blockLen_].hx = static_cast<int16_t>(hx);
    blockLen_++;
  }
  for (uint8_t i = blockLen_ > 0 ? blockLen_ - 1 : 0; i >= 1; i--) {
    uint8_t j = static_cast<uint8_t>(xorshift32(rng_) % (i + 1u));
    Compact t = block_[i];
    block_[i] = block_[j];
    block_[j] = t;
  }
}

void Planner::toStop(int32_t hx, const uint8_t value[4], Stop& out) {
  out.hx = hx;
  out.hy = hy_;
  for (uint8_t k = 0; k < 4; k++) out.us[k] = dose_.us(k, value[k]);
  curX_ = static_cast<int32_t>(h_.originUm[0]) + hx * static_cast<int32_t>(h_.pitchUm[0]);
  if (!passEmitted_) {
    passEmitted_ = true;
    passes_++;
  }
}

bool Planner::next(Stop& out) {
  for (;;) {
    if (!inPass_ && !openPass()) return false;
    if (h_.strategy == Strategy::Random) {
      if (blockPos_ == blockLen_) fillBlock();
      if (blockPos_ < blockLen_) {
        const Compact& c = block_[blockPos_++];
        toStop(c.hx, c.value, out);
        return true;
      }
    } else {
      int32_t hx;
      uint8_t value[4];
      if (mergeNext(hx, value)) {
        toStop(hx, value, out);
        return true;
      }
    }
    inPass_ = false;
  }
}

}  // namespace uv
