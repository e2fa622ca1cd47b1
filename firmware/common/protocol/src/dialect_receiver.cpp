// The Mega's line-acceptance state machine: numbering, duplicates, resend and resync (protocol/mega.md §2).
#include "dialect_receiver.h"

#include <string.h>

#include "crc16.h"
#include "dialect_command.h"
#include "error_codes.h"
#include "progmem.h"
#include "text_scan.h"

namespace uv {

size_t LineReceiver::formatOk(char* out, int32_t line) const {
  size_t n = 0;
  uvMemcpyP(out, UV_P("ok "), 3);
  n = 3;
  if (line >= 0) {
    out[n++] = 'N';
    n += putUnsigned(static_cast<uint32_t>(line), out + n);
    out[n++] = ' ';
  }
  out[n++] = 'P';
  n += putUnsigned(flow_.movesFree(), out + n);
  out[n++] = ' ';
  out[n++] = 'B';
  n += putUnsigned(flow_.windowFree(), out + n);
  uint16_t crc = crc16(out, n);
  out[n++] = '*';
  crc16Hex(crc, out + n);
  n += 4;
  out[n] = '\0';
  return n;
}

void LineReceiver::ok(ReplySink& sink, int32_t n) const {
  char buf[48];
  formatOk(buf, n);
  sink.line(buf);
}

static size_t errorLine(uint8_t code, char* out) {
  uvMemcpyP(out, UV_P("Error:E"), 7);
  size_t n = 7 + putUnsigned(code, out + 7);
  out[n++] = ' ';
  errorMessage(code, out + n, 48);
  return n + strlen(out + n);
}

void LineReceiver::askResend(uint8_t code, ReplySink& sink) {
  resyncing_ = true;
  char buf[96];
  size_t n = errorLine(code, buf);
  uvMemcpyP(buf + n, UV_P(", Last Line: "), 13);
  n += 13;
  n += putSigned(last_, buf + n);
  buf[n] = '\0';
  sink.line(buf);
  uvMemcpyP(buf, UV_P("Resend: "), 8);
  buf[8 + putSigned(last_ + 1, buf + 8)] = '\0';
  sink.line(buf);
  ok(sink);  // a resend request accepts no line
}

bool LineReceiver::m110(const Frame& f, int32_t& setTo) const {
  Command c;
  if (parseCommand(f.body, f.bodyLen, c) != 0 || !c.is('M', 110)) return false;
  if (c.hasValue('N') && c.value('N') >= -1000 && c.value('N') % 1000 == 0) {
    setTo = c.value('N') / 1000;
    return true;
  }
  setTo = f.n;
  return f.hasN;
}

Acceptance LineReceiver::accept(const char* text, uint8_t len, bool overflow, ReplySink& sink, Frame& f) {
  if (!overflow && len == 0) return Acceptance::None;
  f = parseFrame(text, len, overflow);
  if (f.error) {
    if (f.numbered && isLineError(f.error)) {
      askResend(f.error, sink);
    } else {
      char buf[96];
      errorLine(f.error, buf);
      sink.line(buf);
      ok(sink);
    }
    return Acceptance::Replied;
  }
  int32_t setTo = 0;
  if (m110(f, setTo)) {
    last_ = setTo;
    answered_ = setTo;
    resyncing_ = false;
    ok(sink, setTo);  // for -1, an ok without N
    return Acceptance::Replied;
  }
  if (!f.hasN) {
    if (f.bodyLen) return Acceptance::Execute;
    ok(sink);
    return Acceptance::Replied;
  }
  // Numbers do not wrap: after the largest there is no next line, only M110 (protocol/mega.md §2). As
  // last_ never passes kMaxLineNumber, last_ + 1 (here and in askResend) always fits.
  static_assert(kMaxLineNumber < 2147483647u, "last_ + 1 must fit an int32_t");
  if (f.n == last_ + 1) {
    last_ = f.n;
    resyncing_ = false;
    if (f.bodyLen) return Acceptance::Execute;
    markAnswered(f.n);
    ok(sink, f.n);
    return Acceptance::Replied;
  }
  if (f.n <= last_) {
    // A duplicate: confirm a line already answered; for one still waiting or running, free the
    // slot and let its own reply answer it (protocol/mega.md §2).
    ok(sink, f.n <= answered_ ? f.n : -1);
    return Acceptance::Replied;
  }
  if (resyncing_) {
    ok(sink);
    return Acceptance::Replied;
  }
  askResend(kLineSequence, sink);
  return Acceptance::Replied;
}

}  // namespace uv
