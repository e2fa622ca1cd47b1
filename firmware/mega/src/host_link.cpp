// One host-facing port: accepted lines from the line ring, replies through the transmit ring.
#include "host_link.h"

#include <string.h>

#include "error_codes.h"
#include "progmem.h"
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

void HostLink::put(const char* text, uint8_t n, bool flash) {
  for (uint8_t i = 0; i < n; i++) {
    txBuf_[txIn_] = flash ? static_cast<char>(uvFlashByte(text + i)) : text[i];
    txIn_ = txIn_ + 1 == kTxRing ? 0 : static_cast<uint8_t>(txIn_ + 1);
  }
}

bool HostLink::write(const char* text, bool flash) {
  // A line goes out whole or not at all: a line cut at the ring's end would run into the next
  // one, and the host would read neither (protocol/mega.md §1).
  size_t n = flash ? uvStrlenP(text) : strlen(text);
  if (n + 1 > txFree()) return false;
  put(text, static_cast<uint8_t>(n), flash);
  put("\n", 1);
  tx_.kick();
  return true;
}

void HostLink::line(const char* text, bool flash) {
  // Callers of a reply make room first; one that did not is counted (M821's tx_dropped), and its
  // line is not sent in part.
  if (!write(text, flash) && txDropped_ < 0xFFFF) txDropped_++;
}

bool HostLink::poll() {
  bool stop = false;
  // The receiver may answer at once (errors, resend, duplicates): only with room for that.
  for (LineSlot* s; (s = ring_.arrived()) != nullptr && txFree() >= kAcceptRoom;) {
    heard_ = true;
    if (!s->overflow && isEmergencyStop(s->text, s->len)) stop = true;
    uv::Frame frame;
    uv::Acceptance a = receiver_.accept(s->text, s->len, s->overflow, *this, frame);
    if (a == uv::Acceptance::Execute) {
      // The body is kept in place: move it to the slot's start so it reads as one string.
      s->n = frame.hasN ? frame.n : -1;
      uint8_t len = frame.bodyLen;
      memmove(s->text, frame.body, len);
      s->text[len] = 0;
      s->len = len;
    }
    ring_.accepted(a != uv::Acceptance::Execute);
  }
  return stop;
}

void HostLink::ok() {
  LineSlot* s = ring_.front();
  if (!s) return;
  int32_t n = s->n;
  ring_.pop();
  receiver_.markAnswered(n);
  receiver_.ok(*this, n);  // after freeing the slot: B counts it free
}

void HostLink::errorLine(uint8_t code, const char* detail, bool flash) {
  // A refusal leaves the machine as it was and is answered as Marlin answers one, with echo:, so hosts
  // such as OctoPrint stay connected; link errors and faults are Error: (protocol/mega.md §2).
  lastError = code;
  char buf[112];
  size_t n = uv::isRefusal(code) ? 6 : 7;
  uvMemcpyP(buf, uv::isRefusal(code) ? UV_P("echo:E") : UV_P("Error:E"), n);
  n += uv::putUnsigned(code, buf + n);
  buf[n++] = ' ';
  uv::errorMessage(code, buf + n, static_cast<uint8_t>(sizeof buf - n));
  n += strlen(buf + n);
  if (detail) {
    memcpy(buf + n, ": ", 2);
    n += 2;
    size_t d = flash ? uvStrlenP(detail) : strlen(detail);
    if (d > sizeof buf - n - 1) d = sizeof buf - n - 1;
    if (flash) uvMemcpyP(buf + n, detail, d);
    else memcpy(buf + n, detail, d);
    n += d;
  }
  buf[n] = 0;
  line(buf);
}

}  // namespace mega
