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

Colour flashColour(char op) {
  switch (op) {
    case 'F': return Colour::Purple;
    case 'D': case 'U': case 'X': case 'P': return Colour::Cyan;
    case 'R': return Colour::Orange;
    default: return Colour::DimWhite;  // S T E V
  }
}

bool nanoLineUsable(const char* text, uint8_t len, bool overflow) {
  return !overflow && isPrintable(text, len);
}

bool parseNanoCommand(const char* line, uint8_t len, NanoCommand& out) {
  if (len == 1 && strchr("SDUXPTREV", line[0]) && line[0] != '\0') {
    out.op = line[0];
    return true;
  }
  if (len < 2 || line[0] != 'F' || line[1] != ':') return false;
  const char* p = line + 2;
  const char* end = line + len;
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
  }
  tmp[n++] = '\n';
  if (n + 1 > size) return 0;
  memcpy(out, tmp, n);
  out[n] = '\0';
  return n;
}

size_t formatDeciC(int16_t deciC, char* out) {
  size_t n = 0;
  int32_t a = deciC;
  if (a < 0) {
    out[n++] = '-';
    a = -a;
  }
  n += putUnsigned(static_cast<uint32_t>(a / 10), out + n);
  out[n++] = '.';
  out[n++] = static_cast<char>('0' + a % 10);
  return n;
}

size_t formatNanoReply(const NanoReply& r, char* out, size_t size) {
  char tmp[64];
  size_t n = 0;
  tmp[n++] = r.op;
  tmp[n++] = ':';
  switch (r.op) {
    case 'S': n += putUnsigned(r.mask, tmp + n); break;
    case 'P': tmp[n++] = r.triggered ? '1' : '0'; break;
    case 'E': n += putUnsigned(r.flags, tmp + n); break;
    case 'T':
      for (uint8_t i = 0; i < kSensorCount; i++) {
        if (i) tmp[n++] = ',';
        n += formatDeciC(r.deciC[i], tmp + n);
      }
      break;
    case 'V': {
      n += putUnsigned(r.protocol, tmp + n);
      tmp[n++] = ',';
      size_t f = strlen(r.firmware);
      memcpy(tmp + n, r.firmware, f);
      n += f;
      break;
    }
    default: return 0;
  }
  tmp[n++] = '\n';
  if (n + 1 > size) return 0;
  memcpy(out, tmp, n);
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
