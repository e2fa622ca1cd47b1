// Replies and reports of the Mega dialect: canonical format (Mega side) and typed parse (ESP side).
#include "dialect_reply.h"

#include <string.h>

#include "dialect_command.h"
#include "crc16.h"
#include "dialect_frame.h"
#include "error_codes.h"
#include "progmem.h"
#include "text_scan.h"

namespace uv {

const char kMachineType[] UV_FLASH = "UV-LED exposure printer";

namespace {

// The names live in flash on the Mega; every read goes through uvFlashPtr and the uvP functions.
const char kIdle[] UV_FLASH = "idle", kUploading[] UV_FLASH = "uploading", kReady[] UV_FLASH = "ready",
           kRunning[] UV_FLASH = "running", kPaused[] UV_FLASH = "paused", kDone[] UV_FLASH = "done",
           kAborted[] UV_FLASH = "aborted", kFailed[] UV_FLASH = "failed", kInterrupted[] UV_FLASH = "interrupted";
const char* const kJobStates[] UV_FLASH = {kIdle, kUploading, kReady, kRunning, kPaused, kDone, kAborted, kFailed, kInterrupted};
const char kTriggered[] UV_FLASH = "triggered", kOpen[] UV_FLASH = "open", kAlarm[] UV_FLASH = "alarm",
           kDeployed[] UV_FLASH = "deployed", kStowed[] UV_FLASH = "stowed";
const char* const kProbeStates[] UV_FLASH = {kTriggered, kOpen, kAlarm, kDeployed, kStowed};

// Index of [p, end) in a list of names in flash, or -1.
int8_t lookup(const char* p, const char* end, const char* const* names, uint8_t count) {
  size_t n = static_cast<size_t>(end - p);
  for (uint8_t i = 0; i < count; i++) {
    const char* name = uvFlashPtr(names[i]);
    if (uvStrlenP(name) == n && uvMemcmpP(p, name, n) == 0) return static_cast<int8_t>(i);
  }
  return -1;
}

void setText(Reply& r, const char* p, const char* end) {
  r.text = p;
  r.textLen = static_cast<uint8_t>(end - p);
}

// ` key=value` words: key [a-z_]+, value one or more non-space bytes.
bool validFields(const char* p, const char* end) {
  while (p < end) {
    if (*p++ != ' ') return false;
    const char* key = p;
    while (p < end && ((*p >= 'a' && *p <= 'z') || *p == '_')) p++;
    if (p == key || p >= end || *p++ != '=') return false;
    const char* value = p;
    while (p < end && *p != ' ') p++;
    if (p == value) return false;
  }
  return true;
}

// `-?d{1,7}.ddd` as thousandths.
const char* scanMm(const char* p, const char* end, int32_t& out) {
  const char* s = p;
  if (p < end && *p == '-') p++;
  const char* digits = p;
  while (p < end && *p >= '0' && *p <= '9') p++;
  if (p == digits || p - digits > 7 || p + 4 > end || p[0] != '.') return nullptr;
  for (uint8_t i = 1; i <= 3; i++)
    if (p[i] < '0' || p[i] > '9') return nullptr;
  p += 4;
  return parseMilli(s, static_cast<uint8_t>(p - s), out) ? p : nullptr;
}

const char* scanInt(const char* p, const char* end, int32_t& out) {
  bool neg = p < end && *p == '-';
  if (neg) p++;
  uint32_t v = 0;
  p = scanUnsigned(p, end, 10, 2147483647u, v);
  out = neg ? -static_cast<int32_t>(v) : static_cast<int32_t>(v);
  return p;
}

const char* expect(const char* p, const char* end, const char* literal) {
  return (p && startsWith(p, end, literal)) ? p + strlen(literal) : nullptr;
}

// `T:<hottest> /0.0`, then `S<i>:<v> /0.0` for each sensor: nothing heats, so no target (mega.md §4).
bool parseTemps(const char* p, const char* end, Reply& r) {
  int16_t hot = 0;
  p = scanDeci(p + 2, end, 3, hot);
  p = expect(p, end, " /0.0");
  for (uint8_t i = 0; i < kSensorCount && p; i++) {
    char tag[5] = {' ', 'S', static_cast<char>('0' + i), ':', '\0'};
    p = expect(p, end, tag);
    if (p) p = scanDeci(p, end, 3, r.deciC[i]);
    p = expect(p, end, " /0.0");
  }
  return p == end;
}

bool parsePosition(const char* p, const char* end, Reply& r) {
  static const char* const kAxes[] = {"X:", " Y:", " Z:"};
  for (uint8_t i = 0; i < 3 && p; i++) {
    p = expect(p, end, kAxes[i]);
    if (p) p = scanMm(p, end, r.um[i]);
  }
  int32_t e = 0;
  p = expect(p, end, " E:");
  if (p) p = scanMm(p, end, e);
  static const char* const kCounts[] = {" Count X:", " Y:", " Z:"};
  for (uint8_t i = 0; i < 3 && p; i++) {
    p = expect(p, end, kCounts[i]);
    if (p) p = scanInt(p, end, r.steps[i]);
  }
  return p == end;
}

bool parseBed(const char* p, const char* end, Reply& r) {
  static const char* const kAxes[] = {"Bed X: ", " Y: ", " Z: "};
  for (uint8_t i = 0; i < 3 && p; i++) {
    p = expect(p, end, kAxes[i]);
    if (p) p = scanMm(p, end, r.um[i]);
  }
  return p == end;
}

// `<word><fields>` after a prefix, where word is one of names.
bool parseNamedFields(const char* p, const char* end, const char* const* names, uint8_t count, Reply& r) {
  const char* w = p;
  while (p < end && *p != ' ') p++;
  int8_t i = lookup(w, p, names, count);
  if (i < 0 || !validFields(p, end)) return false;
  r.state = static_cast<uint8_t>(i);
  setText(r, p, end);
  return true;
}

bool parseCoded(const char* p, const char* end, Reply& r) {
  uint32_t code = 0;
  if (p >= end || *p != 'E') return false;
  p = scanUnsigned(p + 1, end, 4, 9999, code);
  if (!p || p >= end || *p != ' ') return false;
  r.code = static_cast<uint16_t>(code);
  setText(r, p + 1, end);
  return true;
}

}  // namespace

const char* jobStateName(JobState s) { return uvFlashPtr(kJobStates[static_cast<uint8_t>(s)]); }

bool parseReply(const char* line, uint8_t len, Reply& r) {
  memset(&r, 0, sizeof(r));
  const char* end = line + len;
  const char* p = line;
  if ((len == 2 && startsWith(p, end, "ok")) || startsWith(p, end, "ok ")) {
    r.kind = ReplyKind::Ok;
    uint32_t pv = 0, bv = 0;
    const char* q = expect(p, end, "ok ");
    if (q && q < end && *q == 'N') {
      q = scanUnsigned(q + 1, end, 10, 0xFFFFFFFFu, r.n);
      r.hasN = q != nullptr;
      q = expect(q, end, " ");
    }
    q = expect(q, end, "P");
    if (q) q = scanUnsigned(q, end, 5, 65535, pv);
    q = expect(q, end, " B");
    if (q) q = scanUnsigned(q, end, 5, 65535, bv);
    // The flow fields count only with an intact CRC (protocol/mega.md §2).
    const char* star = q;
    q = expect(q, end, "*");
    char want[5] = "";
    if (q) crc16Hex(crc16(line, static_cast<size_t>(star - line)), want);
    r.hasFlow = q && end - q == 4 && memcmp(q, want, 4) == 0;
    if (!r.hasFlow) {
      r.n = 0;
      r.hasN = false;
    }
    r.p = static_cast<uint16_t>(pv);
    r.b = static_cast<uint16_t>(bv);
    return true;
  }
  if (startsWith(p, end, "Error:")) {
    r.kind = ReplyKind::Error;
    if (!parseCoded(p + 6, end, r)) {
      r.code = 0;
      setText(r, p + 6, end);
    }
    return true;
  }
  if (startsWith(p, end, "Resend:") || startsWith(p, end, "rs ")) {
    r.kind = ReplyKind::Resend;
    p += (*p == 'R') ? 7 : 3;
    if (*line == 'R' && p < end && *p == ' ') p++;
    return scanUnsigned(p, end, 10, 0xFFFFFFFFu, r.n) == end;
  }
  if (startsWith(p, end, "T:")) {
    r.kind = ReplyKind::Temps;
    return parseTemps(p, end, r);
  }
  if (startsWith(p, end, "X:")) {
    r.kind = ReplyKind::Position;
    return parsePosition(p, end, r);
  }
  if (startsWith(p, end, "Bed X:")) {
    r.kind = ReplyKind::ProbePoint;
    return parseBed(p, end, r);
  }
  if (startsWith(p, end, "DOSE:")) {
    r.kind = ReplyKind::Dose;
    return parseDoseReport(p + 5, end, r.dose);
  }
  if (startsWith(p, end, "JOB:")) {
    r.kind = ReplyKind::Job;
    return parseNamedFields(p + 4, end, kJobStates, 9, r);
  }
  if (startsWith(p, end, "PROBE:")) {
    r.kind = ReplyKind::Probe;
    int8_t i = lookup(p + 6, end, kProbeStates, 5);
    r.state = static_cast<uint8_t>(i);
    return i >= 0;
  }
  if (startsWith(p, end, "TEST:")) {
    static const char kQuick[] UV_FLASH = "quick", kFull[] UV_FLASH = "full";
    static const char* const kModes[] UV_FLASH = {kQuick, kFull};
    r.kind = ReplyKind::Test;
    return parseNamedFields(p + 5, end, kModes, 2, r);
  }
  if (startsWith(p, end, "FAULT:")) {
    r.kind = ReplyKind::Fault;
    return parseCoded(p + 6, end, r);
  }
  if (startsWith(p, end, "echo:")) {
    // `echo:E<code> …` is a refusal (mega.md §2): still the command's error to a host that reads codes.
    r.kind = parseCoded(p + 5, end, r) ? ReplyKind::Error : ReplyKind::Echo;
    if (r.kind == ReplyKind::Echo) {
      r.code = 0;
      setText(r, p + 5, end);
    }
    return true;
  }
  if (startsWith(p, end, "busy:")) {
    r.kind = ReplyKind::Busy;
    return true;
  }
  if (len == 5 && startsWith(p, end, "start")) {
    r.kind = ReplyKind::Start;
    return true;
  }
  if (startsWith(p, end, "FIRMWARE_NAME:")) {
    r.kind = ReplyKind::Firmware;
    const char* name = p + 14;
    for (const char* q = name + 1; q < end; q++) {
      const char* v = expect(q, end, " PROTOCOL_VERSION:");
      if (!v) continue;
      const char* after = scanUnsigned(v, end, 5, 65535, r.value);
      if (after && (after == end || *after == ' ')) {
        setText(r, name, q);
        return true;
      }
      return false;
    }
    return false;
  }
  if (startsWith(p, end, "Cap:")) {
    r.kind = ReplyKind::Cap;
    const char* name = p + 4;
    const char* q = name;
    while (q < end && ((*q >= 'A' && *q <= 'Z') || (*q >= '0' && *q <= '9') || *q == '_')) q++;
    if (q == name || q >= end || *q != ':') return false;
    setText(r, name, q);
    return scanUnsigned(q + 1, end, 10, 0xFFFFFFFFu, r.value) == end;
  }
  r.kind = ReplyKind::Other;
  setText(r, p, end);
  return true;
}

namespace {

// Appends to a bounded buffer; remembers overflow.
struct Out {
  char* buf;
  size_t size;
  size_t n;
  bool full;
  void put(const char* s, size_t len) {
    if (n + len + 1 > size) {
      full = true;
      return;
    }
    memcpy(buf + n, s, len);
    n += len;
  }
  void put(const char* s) { put(s, strlen(s)); }
  // A string in flash (UV_P, or a UV_FLASH array).
  void putP(const char* s) {
    size_t len = uvStrlenP(s);
    if (n + len + 1 > size) {
      full = true;
      return;
    }
    uvMemcpyP(buf + n, s, len);
    n += len;
  }
  void num(int32_t v) {
    char t[12];
    put(t, putSigned(v, t));
  }
  void deci(int16_t v) {
    char t[8];
    put(t, formatDeciC(v, t));
  }
  void mm(int32_t v) {
    char t[16];
    size_t k = 0;
    uint32_t a = v < 0 ? static_cast<uint32_t>(-v) : static_cast<uint32_t>(v);
    if (v < 0) t[k++] = '-';
    k += putUnsigned(a / 1000, t + k);
    t[k++] = '.';
    uint32_t f = a % 1000;
    t[k++] = static_cast<char>('0' + f / 100);
    t[k++] = static_cast<char>('0' + f / 10 % 10);
    t[k++] = static_cast<char>('0' + f % 10);
    put(t, k);
  }
};

}  // namespace

size_t formatReply(const Reply& r, char* buf, size_t size) {
  if (r.kind == ReplyKind::Dose) return formatDoseReport(r.dose, buf, size);
  Out o{buf, size, 0, false};
  switch (r.kind) {
    case ReplyKind::Ok:
      o.putP(UV_P("ok"));
      if (r.hasFlow) {
        if (r.hasN) {
          o.putP(UV_P(" N"));
          o.num(static_cast<int32_t>(r.n));
        }
        o.putP(UV_P(" P"));
        o.num(r.p);
        o.putP(UV_P(" B"));
        o.num(r.b);
        char t[6];
        t[0] = '*';
        crc16Hex(crc16(o.buf, o.n), t + 1);
        o.put(t, 5);
      }
      break;
    case ReplyKind::Error:
    case ReplyKind::Fault:
      if (r.kind == ReplyKind::Fault) o.putP(UV_P("FAULT:"));
      else o.putP(r.code && isRefusal(static_cast<uint8_t>(r.code)) ? UV_P("echo:") : UV_P("Error:"));
      if (r.code) {
        o.putP(UV_P("E"));
        o.num(r.code);
        o.putP(UV_P(" "));
      }
      o.put(r.text, r.textLen);
      break;
    case ReplyKind::Resend:
      o.putP(UV_P("Resend: "));
      o.num(static_cast<int32_t>(r.n));
      break;
    case ReplyKind::Temps: {
      // Hosts read `T:` as a hotend and `Tn:` as more of them, and every `/` value as a heater's target:
      // one `T:` and the sensors as `S0`-`S5` (OctoPrint keeps them as custom sensors), all with target
      // 0.0. The soft limits are config (`M850 thermal.limit.<i>`), never a target a host would show.
      uint8_t hot = 0;
      for (uint8_t i = 1; i < kSensorCount; i++)
        if (r.deciC[i] > r.deciC[hot]) hot = i;
      o.putP(UV_P("T:"));
      o.deci(r.deciC[hot]);
      o.putP(UV_P(" /0.0"));
      for (uint8_t i = 0; i < kSensorCount; i++) {
        char tag[5] = {' ', 'S', static_cast<char>('0' + i), ':', '\0'};
        o.put(tag);
        o.deci(r.deciC[i]);
        o.putP(UV_P(" /0.0"));
      }
      break;
    }
    case ReplyKind::Position:
      o.putP(UV_P("X:"));
      o.mm(r.um[0]);
      o.putP(UV_P(" Y:"));
      o.mm(r.um[1]);
      o.putP(UV_P(" Z:"));
      o.mm(r.um[2]);
      o.putP(UV_P(" E:0.000 Count X:"));
      o.num(r.steps[0]);
      o.putP(UV_P(" Y:"));
      o.num(r.steps[1]);
      o.putP(UV_P(" Z:"));
      o.num(r.steps[2]);
      break;
    case ReplyKind::ProbePoint:
      o.putP(UV_P("Bed X: "));
      o.mm(r.um[0]);
      o.putP(UV_P(" Y: "));
      o.mm(r.um[1]);
      o.putP(UV_P(" Z: "));
      o.mm(r.um[2]);
      break;
    case ReplyKind::Job:
      o.putP(UV_P("JOB:"));
      o.putP(uvFlashPtr(kJobStates[r.state]));
      o.put(r.text, r.textLen);
      break;
    case ReplyKind::Probe:
      o.putP(UV_P("PROBE:"));
      o.putP(uvFlashPtr(kProbeStates[r.state]));
      break;
    case ReplyKind::Test:
      o.putP(r.state ? UV_P("TEST:full") : UV_P("TEST:quick"));
      o.put(r.text, r.textLen);
      break;
    case ReplyKind::Echo:
      o.putP(UV_P("echo:"));
      o.put(r.text, r.textLen);
      break;
    case ReplyKind::Busy: o.putP(UV_P("busy: processing")); break;
    case ReplyKind::Start: o.putP(UV_P("start")); break;
    case ReplyKind::Firmware:
      o.putP(UV_P("FIRMWARE_NAME:"));
      o.put(r.text, r.textLen);
      o.putP(UV_P(" PROTOCOL_VERSION:"));
      o.num(static_cast<int32_t>(r.value));
      o.putP(UV_P(" MACHINE_TYPE:"));
      o.putP(kMachineType);
      o.putP(UV_P(" LEDS:4 SENSORS:6"));
      break;
    case ReplyKind::Cap:
      o.putP(UV_P("Cap:"));
      o.put(r.text, r.textLen);
      o.putP(UV_P(":"));
      o.num(static_cast<int32_t>(r.value));
      break;
    case ReplyKind::Other: o.put(r.text, r.textLen); break;
    case ReplyKind::Dose: break;  // above
  }
  if (o.full) return 0;
  buf[o.n] = '\0';
  return o.n;
}

}  // namespace uv
