// Codec for the Mega <-> Nano printhead link (protocol/nano.md): commands, replies, colours.
#include "nano_codec.h"

#include <string.h>

#include "line_splitter.h"
#include "text_scan.h"

namespace uv {

Rgb colourRgb(Colour c) {
  switch (c) {
    case Colour::Green: return {0, 40, 0};
    case Colour::DimWhite: return {24, 24, 24};
    case Colour::Purple: return {96, 0, 128};
    case Colour::Cyan: return {0, 96, 96};
    case Colour::Orange: return {160, 48, 0};
    case Colour::Red: return {128, 0, 0};
  }
  return {0, 0, 0};
}

// Comparisons, not a switch: the AVR compiler made the switch a 21-byte table in the Nano's RAM.
Colour flashColour(char op) {
  if (op == 'F' || op == 'G') return Colour::Purple;
  if (op == 'D' || op == 'U' || op == 'X' || op == 'P') return Colour::Cyan;
  if (op == 'R') return Colour::Orange;
  return Colour::DimWhite;  // S T E V C A B K Q W L O
}

bool nanoLineUsable(const char* text, uint8_t len, bool overflow) {
  return !overflow && isPrintable(text, len);
}

bool parseNanoCommand(const char* line, uint8_t len, NanoCommand& out) {
  if (len == 1) {
    switch (line[0]) {  // a switch, not strchr over a string: on the AVR that string would sit in RAM
      case 'S': case 'D': case 'U': case 'X': case 'P': case 'T': case 'R':
      case 'E': case 'V': case 'C': case 'G': case 'Q': case 'W': case 'O':
        out.op = line[0];
        return true;
      default:
        return false;
    }
  }
  if (len < 2 || line[1] != ':') return false;
  const char* p = line + 2;
  const char* end = line + len;
  if (line[0] == 'L') {  // a speed not in the table is malformed: refused, never rounded or wrapped
    p = scanUnsigned(p, end, 10, 0xFFFFFFFFu, out.baud);
    if (p != end || !nanoLinkBaud(out.baud)) return false;
    out.op = 'L';
    return true;
  }
  if (line[0] != 'F') return false;
  uint32_t fields[5];
  for (uint8_t i = 0; i < 5; i++) {
    if (i > 0) {
      if (p >= end || *p != ',') return false;
      p++;
    }
    p = scanUnsigned(p, end, 10, 0xFFFFFFFFu, fields[i]);
    if (!p) return false;
  }
  if (p != end || fields[0] > 15) return false;
  out.op = 'F';
  out.mask = static_cast<uint8_t>(fields[0]);
  for (uint8_t i = 0; i < kLedCount; i++) out.durations[i] = fields[i + 1];
  return true;
}

size_t formatNanoCommand(const NanoCommand& cmd, char* out, size_t size) {
  if (cmd.op == 'F' && cmd.mask > 15) return 0;  // no such LEDs: refused, not sent for the Nano to reject
  if (cmd.op == 'L' && !nanoLinkBaud(cmd.baud)) return 0;  // no such speed: likewise
  char tmp[64];
  size_t n = 0;
  tmp[n++] = cmd.op;
  if (cmd.op == 'F') {
    tmp[n++] = ':';
    n += putUnsigned(cmd.mask, tmp + n);
    for (uint8_t i = 0; i < kLedCount; i++) {
      tmp[n++] = ',';
      n += putUnsigned(cmd.durations[i], tmp + n);
    }
  } else if (cmd.op == 'L') {
    tmp[n++] = ':';
    n += putUnsigned(cmd.baud, tmp + n);
  }
  tmp[n++] = '\n';
  if (n + 1 > size) return 0;
  memcpy(out, tmp, n);
  out[n] = '\0';
  return n;
}

namespace {
// One decimal digit of `a` at place `power`, by subtraction (AVRs have no divide instruction).
inline char digitAt(uint16_t& a, uint16_t power) {
  char c = '0';
  while (a >= power) {
    a = static_cast<uint16_t>(a - power);
    c++;
  }
  return c;
}
}  // namespace

size_t formatDeciC(int16_t deciC, char* out) {
  size_t n = 0;
  uint16_t a = static_cast<uint16_t>(deciC < 0 ? -static_cast<int32_t>(deciC) : deciC);
  if (deciC < 0) out[n++] = '-';
  char d[4] = {digitAt(a, 10000), digitAt(a, 1000), digitAt(a, 100), digitAt(a, 10)};
  uint8_t first = 0;
  while (first < 3 && d[first] == '0') first++;  // the whole part keeps at least one digit
  for (uint8_t i = first; i < 4; i++) out[n++] = d[i];
  out[n++] = '.';
  out[n++] = static_cast<char>('0' + a);
  return n;
}

size_t formatNanoReply(const NanoReply& r, char* out, size_t size) {
  if (size < kNanoReplyMax) return 0;  // written in place: the caller's buffer must fit any reply
  size_t n = 0;
  out[n++] = r.op;
  out[n++] = ':';
  switch (r.op) {
    case 'S': n += putUnsigned(r.mask, out + n); break;
    case 'P': out[n++] = r.triggered ? '1' : '0'; break;
    case 'E': n += putUnsigned(r.flags, out + n); break;
    case 'C':
      n += putUnsigned(r.boot, out + n);
      out[n++] = ',';
      n += putUnsigned(r.fires, out + n);
      out[n++] = ',';
      out[n++] = r.whole ? '1' : '0';
      break;
    case 'T':
      for (uint8_t i = 0; i < kSensorCount; i++) {
        if (i) out[n++] = ',';
        n += formatDeciC(r.deciC[i], out + n);
      }
      break;
    case 'K': n += putUnsigned(r.code, out + n); break;
    case 'W': n += putUnsigned(r.us, out + n); break;
    case 'L': n += putUnsigned(r.baud, out + n); break;
    case 'O':
      n += putUnsigned(r.exposure, out + n);
      if (r.exposure == 0) break;  // no record waits
      out[n++] = ',';
      n += putUnsigned(r.program, out + n);
      for (uint8_t i = 0; i < kLedCount; i++) {
        out[n++] = ',';
        n += putUnsigned(r.onUs[i], out + n);
      }
      break;
    case 'Q':
      n += putUnsigned(r.free, out + n);
      out[n++] = ',';
      n += putUnsigned(r.armed, out + n);
      out[n++] = ',';
      n += putUnsigned(r.pass, out + n);
      break;
    case 'V': {
      n += putUnsigned(r.protocol, out + n);
      out[n++] = ',';
      size_t f = strnlen(r.firmware, sizeof r.firmware - 1);
      memcpy(out + n, r.firmware, f);
      n += f;
      break;
    }
    default: return 0;
  }
  out[n++] = '\n';
  out[n] = '\0';
  return n;
}

static bool firmwareChar(char c) {
  return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '.' || c == '+' || c == '-';
}

bool parseNanoReply(const char* line, size_t len, NanoReply& r) {
  if (len < 3 || line[len - 1] != '\n' || line[1] != ':') return false;
  const char* p = line + 2;
  const char* end = line + len - 1;
  r.op = line[0];
  uint32_t v = 0;
  switch (r.op) {
    case 'S':
      p = scanUnsigned(p, end, 2, 15, v);
      r.mask = static_cast<uint8_t>(v);
      return p == end;
    case 'P':
      if (end - p != 1 || (*p != '0' && *p != '1')) return false;
      r.triggered = *p == '1';
      return true;
    case 'E':
      p = scanUnsigned(p, end, 3, 255, v);
      r.flags = static_cast<uint8_t>(v);
      return p == end;
    case 'K':
      p = scanUnsigned(p, end, 1, 7, v);
      r.code = static_cast<uint8_t>(v);
      return p == end;
    case 'W':
      p = scanUnsigned(p, end, 10, 0xFFFFFFFFu, r.us);
      return p == end;
    case 'L':
      p = scanUnsigned(p, end, 10, 0xFFFFFFFFu, r.baud);
      return p == end && nanoLinkBaud(r.baud);
    case 'O': {
      p = scanUnsigned(p, end, 10, 0xFFFFFFFFu, r.exposure);
      if (!p) return false;
      if (r.exposure == 0) return p == end;  // none waits; a record is never numbered 0
      if (p >= end || *p != ',') return false;
      p = scanUnsigned(p + 1, end, 5, 65535, v);
      if (!p) return false;
      r.program = static_cast<uint16_t>(v);
      for (uint8_t i = 0; i < kLedCount; i++) {
        if (p >= end || *p != ',') return false;
        p = scanUnsigned(p + 1, end, 10, 0xFFFFFFFFu, r.onUs[i]);
        if (!p) return false;
      }
      return p == end;
    }
    case 'Q': {
      uint32_t q[3];  // free, armed, pass
      for (uint8_t i = 0; i < 3; i++) {
        if (i) {
          if (p >= end || *p != ',') return false;
          p++;
        }
        p = scanUnsigned(p, end, 1, i == 2 ? 7 : 2, q[i]);
        if (!p) return false;
      }
      r.free = static_cast<uint8_t>(q[0]);
      r.armed = static_cast<uint8_t>(q[1]);
      r.pass = static_cast<uint8_t>(q[2]);
      return p == end;
    }
    case 'T':
      for (uint8_t i = 0; i < kSensorCount; i++) {
        if (i) {
          if (p >= end || *p != ',') return false;
          p++;
        }
        p = scanDeci(p, end, 3, r.deciC[i]);
        if (!p) return false;
      }
      return p == end;
    case 'C':
      p = scanUnsigned(p, end, 5, 65535, v);
      if (!p || p >= end || *p != ',') return false;
      r.boot = static_cast<uint16_t>(v);
      p = scanUnsigned(p + 1, end, 10, 0xFFFFFFFFu, r.fires);
      if (!p || end - p != 2 || p[0] != ',' || (p[1] != '0' && p[1] != '1')) return false;
      r.whole = p[1] == '1';
      return true;
    case 'V': {
      p = scanUnsigned(p, end, 5, 65535, v);
      if (!p || p >= end || *p != ',') return false;
      r.protocol = static_cast<uint16_t>(v);
      p++;
      size_t n = static_cast<size_t>(end - p);
      if (n < 1 || n > 20) return false;
      for (size_t i = 0; i < n; i++)
        if (!firmwareChar(p[i])) return false;
      memcpy(r.firmware, p, n);
      r.firmware[n] = '\0';
      return true;
    }
    default: return false;
  }
}

}  // namespace uv
