// Scan programs on the printhead link (protocol/nano.md "Scan programs").
#include "scan_program.h"

#include <string.h>
#ifdef __AVR__
#include <util/crc16.h>
#endif

#include "text_scan.h"

namespace uv {

namespace {
// One byte of CRC-16/CCITT-FALSE. On the AVR, avr-libc's XMODEM step (the same polynomial, not
// reflected; only the initial value differs, and that is the caller's): about 20 cycles a byte
// instead of about 100 for the bit loop, which the Nano runs on every event it loads.
inline uint16_t crcByte(uint16_t crc, uint8_t b) {
#ifdef __AVR__
  return _crc_xmodem_update(crc, b);
#else
  crc ^= static_cast<uint16_t>(b << 8);
  for (uint8_t k = 0; k < 8; k++) crc = (crc & 0x8000) ? static_cast<uint16_t>((crc << 1) ^ 0x1021) : static_cast<uint16_t>(crc << 1);
  return crc;
#endif
}
}  // namespace

uint16_t checkEvent(uint16_t crc, uint32_t d, uint8_t m) {
  // The word d × 16 + m, least significant byte first, from d's bytes: 8-bit shifts only (an AVR
  // shifts a 32-bit value one bit per pass of a loop).
  uint8_t b0 = static_cast<uint8_t>(d), b1 = static_cast<uint8_t>(d >> 8), b2 = static_cast<uint8_t>(d >> 16),
          b3 = static_cast<uint8_t>(d >> 24);
  crc = crcByte(crc, static_cast<uint8_t>(b0 << 4 | m));
  crc = crcByte(crc, static_cast<uint8_t>(b1 << 4 | b0 >> 4));
  crc = crcByte(crc, static_cast<uint8_t>(b2 << 4 | b1 >> 4));
  return crcByte(crc, static_cast<uint8_t>(b3 << 4 | b2 >> 4));
}

bool AppendLine::begin(const char* line, uint8_t len) {
  if (len < 3 || line[0] != 'A' || line[1] != ':') return false;
  end_ = line + len;
  uint32_t q;
  p_ = scanUnsigned(line + 2, end_, 5, 65535, q);
  seq_ = static_cast<uint16_t>(q);
  bad_ = !p_ || p_ == end_;  // at least one pair
  return p_ != nullptr;
}

bool AppendLine::next(uint32_t& d, uint8_t& m) {
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

bool ProgramWriter::add(uint32_t t, uint8_t m) {
  if (m > 15) return false;
  if (any_ && (t <= last_ || t - last_ > kProgramMaxDelta)) return false;
  if (!any_ && t > kProgramMaxDelta) return false;
  if (events_ == kProgramEvents) seal(true);
  uint32_t d = any_ ? t - last_ : t;
  char pair[16];
  size_t n = 0;
  pair[n++] = ',';
  n += putUnsigned(d, pair + n);
  pair[n++] = ',';
  n += putUnsigned(m, pair + n);
  if (len_ && len_ + n > kNanoMaxLine) flushLine();
  if (!len_) {
    line_[len_++] = 'A';
    line_[len_++] = ':';
    len_ = static_cast<uint8_t>(len_ + putUnsigned(seq_++, line_ + len_));
  }
  memcpy(line_ + len_, pair, n);
  len_ = static_cast<uint8_t>(len_ + n);
  check_ = checkEvent(check_, d, m);
  events_++;
  last_ = t;
  any_ = true;
  return true;
}

void ProgramWriter::flushLine() {
  line_[len_++] = '\n';
  line_[len_] = '\0';
  sink_(ctx_, line_, len_);
  len_ = 0;
}

void ProgramWriter::seal(bool more) {
  if (len_) flushLine();
  Seal s{static_cast<uint8_t>((programs_ ? kSealContinuation : 0) | (more ? kSealMore : 0)), events_, check_};
  char out[24];
  size_t n = formatSeal(s, out);
  sink_(ctx_, out, n);
  programs_++;
  seq_ = 0;
  events_ = 0;
  check_ = kCheckInit;
}

bool ProgramWriter::finish() {
  if (!events_) return false;
  seal(false);
  return true;
}

}  // namespace uv
