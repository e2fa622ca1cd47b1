// One host-facing port: bytes to accepted lines, the accepted-line queue and the transmit ring.
#include "host_link.h"

#include <string.h>

#include "error_codes.h"
#include "text_scan.h"

namespace mega {

bool isEmergencyStop(const char* line, uint8_t len) {
  const char* p = line;
  const char* end = line + len;
  if (p < end && (*p == 'N' || *p == 'n')) {  // skip a line number
    p++;
    if (p < end && *p == '-') p++;
    while (p < end && *p >= '0' && *p <= '9') p++;
    while (p < end && *p == ' ') p++;
  }
  if (end - p < 4 || (p[0] != 'M' && p[0] != 'm') || p[1] != '1' || p[2] != '1' || p[3] != '2') return false;
  return end - p == 4 || p[4] == ' ' || p[4] == '*' || p[4] == ';';
}

void HostLink::put(const char* text, uint16_t n) {
  for (uint16_t i = 0; i < n && txCount_ < kTxRing; i++) {
    tx_[(txHead_ + txCount_) % kTxRing] = text[i];
    txCount_++;
  }
}

void HostLink::line(const char* text) {
  put(text, static_cast<uint16_t>(strlen(text)));
  put("\n", 1);
  pump();
}

uint16_t HostLink::room() const {
  uint16_t free = static_cast<uint16_t>(kTxRing - txCount_);
  return free > kTxReserve ? static_cast<uint16_t>(free - kTxReserve) : 0;
}

bool HostLink::report(const char* text) {
  if (strlen(text) + 1 > room()) return false;
  line(text);
  return true;
}

void HostLink::pump() {
  while (txCount_) {
    uint16_t start = txHead_;
    uint16_t run = txCount_;
    if (start + run > kTxRing) run = static_cast<uint16_t>(kTxRing - start);  // up to the ring's end
    uint8_t n = run > 16 ? 16 : static_cast<uint8_t>(run);
    while (n && !io_.write(tx_ + start, n)) n = static_cast<uint8_t>(n / 2);  // what the UART takes now
    if (!n) return;
    txHead_ = static_cast<uint16_t>((txHead_ + n) % kTxRing);
    txCount_ = static_cast<uint16_t>(txCount_ - n);
  }
}

bool HostLink::poll() {
  bool stop = false;
  pump();
  for (uint8_t budget = 128; budget; budget--) {
    if (!lineWaiting_) {
      int16_t b = io_.read();
      if (b < 0) break;
      if (!splitter_.push(static_cast<char>(b))) continue;
      lineWaiting_ = true;
      heard_ = true;
      if (!splitter_.overflow() && isEmergencyStop(splitter_.text(), splitter_.length())) stop = true;
    }
    // The receiver may answer at once (errors, resend, duplicates): it needs the reserve free.
    // A full queue holds the line back too: only a host that ignores the window meets that.
    if (kTxRing - txCount_ < kTxReserve || count_ == kWindow) break;
    lineWaiting_ = false;
    uv::Frame frame;
    if (receiver_.accept(splitter_.text(), splitter_.length(), splitter_.overflow(), *this, frame) != uv::Acceptance::Execute) continue;
    QueuedLine& q = queue_[(head_ + count_) % kWindow];
    q.n = frame.hasN ? frame.n : -1;
    q.len = frame.bodyLen;
    memcpy(q.body, frame.body, frame.bodyLen);
    q.body[frame.bodyLen] = 0;
    count_++;
  }
  pump();
  return stop;
}

void HostLink::ok() {
  if (!count_) return;
  int32_t n = queue_[head_].n;
  head_ = static_cast<uint8_t>((head_ + 1) % kWindow);
  count_--;
  receiver_.markAnswered(n);
  receiver_.ok(*this, n);  // after freeing the slot: B counts it free
}

void HostLink::errorLine(uint8_t code, const char* detail) {
  char buf[112];
  memcpy(buf, "Error:E", 7);
  size_t n = 7 + uv::putUnsigned(code, buf + 7);
  buf[n++] = ' ';
  uv::errorMessage(code, buf + n, static_cast<uint8_t>(sizeof buf - n));
  n += strlen(buf + n);
  if (detail) {
    memcpy(buf + n, ": ", 2);
    n += 2;
    size_t d = strlen(detail);
    if (d > sizeof buf - n - 1) d = sizeof buf - n - 1;
    memcpy(buf + n, detail, d);
    n += d;
  }
  buf[n] = 0;
  line(buf);
}

}  // namespace mega
