// Scan programs on the printhead link (protocol/nano.md "Scan programs").
#include "scan_program.h"

#include <string.h>

#include "crc16.h"
#include "text_scan.h"

namespace uv {

uint16_t checkEvent(uint16_t crc, uint32_t d, uint8_t m) {
  // The word d × 16 + m, least significant byte first, from d's bytes: 8-bit shifts only (an AVR
  // shifts a 32-bit value one bit per pass of a loop).
  uint8_t b0 = static_cast<uint8_t>(d), b1 = static_cast<uint8_t>(d >> 8), b2 = static_cast<uint8_t>(d >> 16),
          b3 = static_cast<uint8_t>(d >> 24);
  crc = crc16Update(crc, static_cast<uint8_t>(b0 << 4 | m));
  crc = crc16Update(crc, static_cast<uint8_t>(b1 << 4 | b0 >> 4));
  crc = crc16Update(crc, static_cast<uint8_t>(b2 << 4 | b1 >> 4));
  return crc16Update(crc, static_cast<uint8_t>(b3 << 4 | b2 >> 4));
}

uint16_t checkWord(uint16_t crc, uint32_t w) {
  crc = crc16Update(crc, static_cast<uint8_t>(w));
  crc = crc16Update(crc, static_cast<uint8_t>(w >> 8));
  crc = crc16Update(crc, static_cast<uint8_t>(w >> 16));
  return crc16Update(crc, static_cast<uint8_t>(w >> 24));
}

uint8_t packWord(uint32_t w, char* out) {
  char groups[kPackMaxChars];
  uint8_t n = 0;
  do {
    groups[n++] = static_cast<char>(w & 31);
    w >>= 5;
  } while (w);
  for (uint8_t i = 0; i < n; i++) out[i] = static_cast<char>(kPackBase + groups[n - 1 - i] + (i + 1 < n ? kPackMore : 0));
  return n;
}

bool AppendLine::begin(const char* line, uint8_t len) {
  if (len < 3 || (line[0] != 'A' && line[0] != 'B') || line[1] != ':') return false;
  packed_ = line[0] == 'B';
  end_ = line + len;
  uint32_t q;
  p_ = scanUnsigned(line + 2, end_, 5, 65535, q);
  seq_ = static_cast<uint16_t>(q);
  bad_ = !p_ || p_ == end_;  // at least one event
  if (packed_ && !bad_ && (*p_ != ',' || ++p_ == end_)) bad_ = true;
  return p_ != nullptr;
}

bool AppendLine::nextWord(uint32_t& w) {
  if (bad_ || p_ == end_) return false;
  const char* p = p_;
  uint8_t c = static_cast<uint8_t>(*p++ - kPackBase);
  bool ok = c != kPackMore && c < 2 * kPackMore;  // no leading zero bits: one way to write a word
  uint32_t v = c & 31;
  while (ok && (c & kPackMore)) {
    // Five more bits must stay below 2³²; the word must end before the line does.
    if (p == end_ || (v >> 27)) {
      ok = false;
      break;
    }
    c = static_cast<uint8_t>(*p++ - kPackBase);
    ok = c < 2 * kPackMore;
    v = v << 5 | (c & 31);
  }
  if (!ok) {
    bad_ = true;
    return false;
  }
  w = v;
  p_ = p;
  return true;
}

bool AppendLine::next(uint32_t& d, uint8_t& m) {
  if (packed_) {
    uint32_t w;
    if (!nextWord(w)) return false;
    d = w >> 4;
    m = static_cast<uint8_t>(w & 0x0F);
    return true;
  }
  if (bad_ || p_ == end_) return false;
  uint32_t v;
  const char* p = p_;
  if (*p != ',' || !(p = scanUnsigned(p + 1, end_, 9, kProgramMaxDelta, d)) || p == end_ || *p != ',' ||
      !(p = scanUnsigned(p + 1, end_, 2, 15, v))) {
    bad_ = true;
    return false;
  }
  m = static_cast<uint8_t>(v);
  p_ = p;
  return true;
}

bool parseSeal(const char* line, uint8_t len, Seal& out) {
  if (len < 3 || line[0] != 'K' || line[1] != ':') return false;
  const char* end = line + len;
  uint32_t f, n, c;
  const char* p = scanUnsigned(line + 2, end, 1, 3, f);
  if (!p || p == end || *p != ',' || !(p = scanUnsigned(p + 1, end, 2, kProgramEvents, n)) || n == 0) return false;
  if (p == end || *p != ',' || !(p = scanUnsigned(p + 1, end, 5, 65535, c)) || p != end) return false;
  out = {static_cast<uint8_t>(f), static_cast<uint8_t>(n), static_cast<uint16_t>(c)};
  return true;
}

size_t formatSeal(const Seal& s, char* out) {
  size_t n = 0;
  out[n++] = 'K';
  out[n++] = ':';
  n += putUnsigned(s.flags, out + n);
  out[n++] = ',';
  n += putUnsigned(s.events, out + n);
  out[n++] = ',';
  n += putUnsigned(s.check, out + n);
  out[n++] = '\n';
  out[n] = '\0';
  return n;
}

bool ProgramLines::peek() {
  if (have_ || ended_) return have_;
  if (!source_(ctx_, t_, m_)) {
    ended_ = true;
    return false;
  }
  if (m_ > 15 || (any_ && (t_ <= last_ || t_ - last_ > kProgramMaxDelta)) || (!any_ && t_ > kProgramMaxDelta)) {
    ended_ = failed_ = true;
    return false;
  }
  have_ = true;
  return true;
}

uint8_t ProgramLines::seal(char* out) {
  Seal s{static_cast<uint8_t>((programs_ ? kSealContinuation : 0) | (peek() ? kSealMore : 0)), events_, check_};
  programs_++;
  seq_ = 0;
  events_ = 0;
  check_ = kCheckInit;
  return static_cast<uint8_t>(formatSeal(s, out));
}

uint8_t ProgramLines::next(char* out) {
  const bool more = peek();
  if (failed_) return 0;  // the program under way stays unsealed
  if (events_ && (events_ == kProgramEvents || !more)) return seal(out);
  if (!more) return 0;
  uint8_t n = 0;
  out[n++] = 'B';
  out[n++] = ':';
  n = static_cast<uint8_t>(n + putUnsigned(seq_++, out + n));
  out[n++] = ',';
  while (events_ < kProgramEvents && peek()) {
    const uint32_t d = any_ ? t_ - last_ : t_;
    char word[kPackMaxChars];
    const uint8_t p = packWord(d << 4 | m_, word);
    if (n + p > kNanoMaxLine) break;
    memcpy(out + n, word, p);
    n = static_cast<uint8_t>(n + p);
    check_ = checkEvent(check_, d, m_);
    events_++;
    last_ = t_;
    any_ = true;
    have_ = false;
  }
  out[n++] = '\n';
  out[n] = '\0';
  return n;
}

// Program k ≥ 3 goes out only once program k − 2 has played (the Nano holds two) and the Mega has
// learnt so, and must be armed before program k − 1 ends: its lines, a fifth to spare, fit the time
// k − 1 plays less the relay (5 × s_k + 4 × relay ≤ 4 × (e_k−1 − e_k−2)), s_k the longer of their
// time on the wire and the planner's time to make their events.
void LinkLoad::add(const char* line, uint8_t n, uint32_t lastUs) {
  bytes_ += n;
  program_ += n;
  Seal s;
  if (line[0] != 'K' || !parseSeal(line, static_cast<uint8_t>(n - 1), s)) return;
  events_ += s.events;
  if (++sealed_ == 2) {
    ahead_ = bytes_;
    aheadEvents_ = events_;
  }
  if (sealed_ > 2 && !need_) {
    const uint64_t need = 5 * sendUs(program_, s.events, baud_) + 4ull * kProgramRelayUs, have = 4ull * (end1_ - end2_);
    if (need > have) {
      need_ = need;
      have_ = have;
    }
  }
  program_ = 0;
  end2_ = end1_;
  end1_ = lastUs;
}

bool LinkLoad::fits(uint32_t passUs, uint64_t& need, uint64_t& have) const {
  need = sealed_ > 2 ? 5 * sendUs(bytes_ - ahead_, events_ - aheadEvents_, baud_) : 0;
  have = 4ull * passUs;
  if (need > have) return false;
  need = need_;
  have = have_;
  return !need_;
}

}  // namespace uv
