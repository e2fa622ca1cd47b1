// Streaming verifier of job text (protocol/job.md): record syntax, order, bounds and the whole-job CRC.
#include "job_verifier.h"

#include <string.h>

#include "crc32.h"
#include "error_codes.h"
#include "progmem.h"
#include "text_scan.h"

namespace uv {

namespace {

const char kRaster[] UV_FLASH = "raster", kSerpentine[] UV_FLASH = "serpentine", kShortest[] UV_FLASH = "shortest",
           kRandom[] UV_FLASH = "random", kScan[] UV_FLASH = "scan", kMixed[] UV_FLASH = "mixed";
const char* const kStrategies[kStrategyCount] UV_FLASH = {kRaster, kSerpentine, kShortest, kRandom, kScan, kMixed};

// Cursor over single-space separated words.
struct Words {
  Words(const char* begin, const char* stop) : p(begin), end(stop) {}
  const char* p;
  const char* end;
  bool bad = false;

  // Next word as [w, wEnd); false at the end or on an empty word.
  bool next(const char*& w, const char*& wEnd) {
    if (p >= end) return false;
    w = p;
    while (p < end && *p != ' ') p++;
    wEnd = p;
    if (p < end) {
      p++;
      if (p == end) bad = true;  // trailing space
    }
    if (w == wEnd) bad = true;
    return !bad;
  }
  bool done() const { return p >= end && !bad; }
  // The next word is `literal`, a string in flash (UV_P).
  bool is(const char* literal) {
    const char *w, *e;
    return next(w, e) && static_cast<size_t>(e - w) == uvStrlenP(literal) && uvMemcmpP(w, literal, e - w) == 0;
  }
  // `0|-?[1-9][0-9]*` within [lo, hi].
  bool integer(int32_t lo, int32_t hi, int32_t& out) {
    const char *w, *e;
    if (!next(w, e)) return false;
    bool neg = *w == '-';
    if (neg) w++;
    if (w == e || (*w == '0' && (e - w > 1 || neg))) return false;
    uint32_t v = 0;
    if (scanUnsigned(w, e, 10, 0xFFFFFFFFu, v) != e) return false;
    int64_t s = neg ? -static_cast<int64_t>(v) : static_cast<int64_t>(v);
    if (s < lo || s > hi) return false;
    out = static_cast<int32_t>(s);
    return true;
  }
  bool u32(uint32_t lo, uint32_t hi, uint32_t& out) {
    const char *w, *e;
    if (!next(w, e) || (*w == '0' && e - w > 1)) return false;
    if (scanUnsigned(w, e, 10, 0xFFFFFFFFu, out) != e) return false;
    return out >= lo && out <= hi;
  }
};

int8_t hexDigit(char c) {
  if (c >= '0' && c <= '9') return static_cast<int8_t>(c - '0');
  if (c >= 'a' && c <= 'f') return static_cast<int8_t>(c - 'a' + 10);
  return -1;
}

}  // namespace

uint8_t hexCell(const char* hex, uint8_t index) {
  return static_cast<uint8_t>(hexDigit(hex[index * 2]) << 4 | hexDigit(hex[index * 2 + 1]));
}

const char* strategyName(Strategy s) { return uvFlashPtr(kStrategies[static_cast<uint8_t>(s)]); }

uint8_t JobVerifier::push(const char* record, uint8_t len) {
  if (error_) return error_;
  lineNo_++;
  if (ended_) return fail(kJobIncomplete);
  const char* end = record + len;
  if (len >= 4 && uvMemcmpP(record, UV_P("end "), 4) == 0) return endRecord(record + 4, end);
  if (len == 3 && uvMemcmpP(record, UV_P("end"), 3) == 0) return fail(kJobMalformed);
  bool ok = index_ < 10 ? headerRecord(record, end) : segment(record, end);
  if (!ok) return fail(kJobMalformed);
  crc_ = crc32Update(crc_, record, len);
  crc_ = crc32Update(crc_, "\n", 1);
  return 0;
}

uint8_t JobVerifier::finish() {
  if (error_) return error_;
  if (!ended_) return fail(kJobIncomplete);
  return 0;
}

uint8_t JobVerifier::endRecord(const char* p, const char* end) {
  if (index_ < 10 || end - p != 8) return fail(kJobMalformed);
  for (const char* q = p; q < end; q++)
    if (hexDigit(*q) < 0) return fail(kJobMalformed);
  ended_ = true;
  char hex[9];
  crc32Hex(crc_, hex);
  return memcmp(hex, p, 8) == 0 ? 0 : fail(kJobHashMismatch);
}

bool JobVerifier::headerRecord(const char* p, const char* end) {
  Words w{p, end};
  int32_t a = 0, b = 0;
  switch (index_) {
    case 0:
      if (!w.is(UV_P("uvj")) || !w.integer(1, 2, a)) return false;
      format_ = static_cast<uint8_t>(a);
      break;
    case 1:
      if (!w.is(UV_P("grid")) || !w.integer(1, kJobMaxSide, a) || !w.integer(1, kJobMaxSide, b)) return false;
      h_.cols = static_cast<uint16_t>(a);
      h_.rows = static_cast<uint16_t>(b);
      break;
    case 2:
      if (!w.is(UV_P("pitch")) || !w.u32(1, 100000, h_.pitchUm[0]) || !w.u32(1, 100000, h_.pitchUm[1])) return false;
      break;
    case 3:
      if (!w.is(UV_P("origin")) || !w.u32(0, 10000000, h_.originUm[0]) || !w.u32(0, 10000000, h_.originUm[1])) return false;
      break;
    case 4: {
      if (!w.is(UV_P("map"))) return false;
      Words probe = w;
      if (probe.is(UV_P("linear")) && probe.done()) {
        h_.map = DoseMap::Linear;
        h_.level = 0;
        w = probe;
      } else {
        if (!w.is(UV_P("threshold")) || !w.integer(1, 255, a)) return false;
        h_.map = DoseMap::Threshold;
        h_.level = static_cast<uint8_t>(a);
      }
      break;
    }
    case 5: {
      Words probe = w;
      if (probe.is(UV_P("full"))) {
        w = probe;
        h_.byTarget = false;
        if (!w.u32(1, 10000000, h_.fullUs)) return false;
      } else {
        if (!w.is(UV_P("target")) || !w.u32(1, 100000000, h_.targetUJcm2)) return false;
        h_.byTarget = true;
        for (uint8_t i = 0; i < 4; i++)
          if (!w.u32(1, 10000000, h_.irradianceUWcm2[i])) return false;
      }
      break;
    }
    case 6:
      if (!w.is(UV_P("gain"))) return false;
      for (uint8_t i = 0; i < 4; i++) {
        if (!w.integer(1, 10000, a)) return false;
        h_.gainPermille[i] = static_cast<uint16_t>(a);
      }
      break;
    case 7:
      if (!w.is(UV_P("thermal")) || !w.integer(-1000, 1000, a) || !w.integer(-400, 1250, b)) return false;
      h_.thermalCoeff = static_cast<int16_t>(a);
      h_.thermalRefDeciC = static_cast<int16_t>(b);
      break;
    case 8:
      if (!w.is(UV_P("leds"))) return false;
      for (uint8_t i = 0; i < 8; i++) {
        if (!w.integer(-4096, 4096, a)) return false;
        h_.offsets[i / 2][i % 2] = static_cast<int16_t>(a);
      }
      break;
    case 9: {
      if (!w.is(UV_P("strategy"))) return false;
      const char *n, *ne;
      if (!w.next(n, ne)) return false;
      int8_t s = -1;
      for (uint8_t i = 0; i < kStrategyCount; i++) {
        const char* name = uvFlashPtr(kStrategies[i]);
        if (static_cast<size_t>(ne - n) == uvStrlenP(name) && uvMemcmpP(n, name, ne - n) == 0) s = static_cast<int8_t>(i);
      }
      if (s < 0 || !w.u32(0, 0xFFFFFFFFu, h_.seed)) return false;
      h_.strategy = static_cast<Strategy>(s);
      if (h_.strategy != Strategy::Random && h_.seed != 0) return false;
      break;
    }
  }
  if (!w.done()) return false;
  index_++;
  return true;
}

bool JobVerifier::claim(int32_t row, int32_t col, uint16_t cells) {
  if (col + cells > h_.cols) return false;
  if (row < prevRow_ || (row == prevRow_ && col < prevEnd_)) return false;
  prevRow_ = row;
  prevEnd_ = static_cast<uint16_t>(col + cells);
  return true;
}

bool JobVerifier::segment(const char* p, const char* end) {
  if (format_ >= 2 && end - p >= 3 && uvMemcmpP(p, UV_P("rl "), 3) == 0) return runs(p + 3, end);
  Words w{p, end};
  int32_t row = 0, col = 0;
  const char *hex, *hexEnd;
  if (!w.is(UV_P("r")) || !w.integer(0, h_.rows - 1, row) || !w.integer(0, h_.cols - 1, col) || !w.next(hex, hexEnd) || !w.done()) {
    return false;
  }
  size_t digits = static_cast<size_t>(hexEnd - hex);
  if (digits == 0 || digits % 2 || digits > kJobMaxCellsPerRecord * 2u) return false;
  for (const char* q = hex; q < hexEnd; q++)
    if (hexDigit(*q) < 0) return false;
  uint8_t cells = static_cast<uint8_t>(digits / 2);
  if (!claim(row, col, cells)) return false;
  if (sink_) {
    uint8_t buf[kJobMaxCellsPerRecord];
    for (uint8_t i = 0; i < cells; i++) buf[i] = hexCell(hex, i);
    sink_->segment(static_cast<uint16_t>(row), static_cast<uint16_t>(col), buf, cells);
  }
  return true;
}

namespace {

// One token of an `rl` record: literal cells (`hex` set, `count` cells) or a run (`value` `count` times).
struct RunToken {
  const char* hex = nullptr;
  uint16_t count = 0;
  uint8_t value = 0;
};

// Parses [w, e) as a token; false when it is neither 1+ pairs of lower-case hex digits nor `<n>x<hh>`
// with n in kJobMinRun..kJobMaxSide, written without leading zeros.
bool parseToken(const char* w, const char* e, RunToken& t) {
  const char* x = w;
  while (x < e && *x != 'x') x++;
  if (x == e) {
    if ((e - w) % 2) return false;
    for (const char* q = w; q < e; q++)
      if (hexDigit(*q) < 0) return false;
    t.hex = w;
    t.count = static_cast<uint16_t>((e - w) / 2);
    return true;
  }
  uint32_t n = 0;
  if (x == w || *w == '0' || scanUnsigned(w, x, 4, kJobMaxSide, n) != x || n < kJobMinRun) return false;
  if (e - x != 3 || hexDigit(x[1]) < 0 || hexDigit(x[2]) < 0) return false;
  t.hex = nullptr;
  t.count = static_cast<uint16_t>(n);
  t.value = hexCell(x + 1, 0);
  return true;
}

}  // namespace

uint16_t recordPieceBytes(const char* record, uint8_t len, uint8_t head) {
  const char* end = record + len;
  if (len < 2 || record[0] != 'r' || (record[1] != ' ' && record[1] != 'l')) return 0;
  const bool runs = record[1] == 'l';
  uint8_t spaces = 0;
  const char* p = record;
  while (p < end && spaces < 3) spaces = static_cast<uint8_t>(spaces + (*p++ == ' '));
  if (!runs) return static_cast<uint16_t>(head + (end - p) / 2);
  uint32_t bytes = 0;
  while (p < end) {
    const char* w = p;
    while (p < end && *p != ' ') p++;
    RunToken t;
    if (parseToken(w, p, t) && !(t.hex == nullptr && t.value == 0))
      bytes += t.count + static_cast<uint32_t>(head) * ((t.count + kJobMaxCellsPerRecord - 1) / kJobMaxCellsPerRecord);
    if (p < end) p++;
  }
  return bytes > 0xFFFF ? 0xFFFF : static_cast<uint16_t>(bytes);
}

bool JobVerifier::runs(const char* p, const char* end) {
  if (end - p + 3 > kJobMaxRecordBytes) return false;
  Words w{p, end};
  int32_t row = 0, col = 0;
  if (!w.integer(0, h_.rows - 1, row) || !w.integer(0, h_.cols - 1, col)) return false;
  const char* tokens = w.p;
  uint32_t cells = 0;
  const char *t, *te;
  while (w.next(t, te)) {
    RunToken tok;
    if (!parseToken(t, te, tok)) return false;
    cells += tok.count;
  }
  if (!w.done() || cells == 0 || cells > h_.cols) return false;
  if (!claim(row, col, static_cast<uint16_t>(cells))) return false;
  if (!sink_) return true;
  // Every token checked: the cells go out in pieces of at most 32.
  Words again{tokens, end};
  uint8_t buf[kJobMaxCellsPerRecord];
  uint16_t at = static_cast<uint16_t>(col);
  while (again.next(t, te)) {
    RunToken tok;
    parseToken(t, te, tok);
    for (uint16_t done = 0; done < tok.count;) {
      uint8_t n = static_cast<uint8_t>(tok.count - done > kJobMaxCellsPerRecord ? kJobMaxCellsPerRecord : tok.count - done);
      for (uint8_t i = 0; i < n; i++) buf[i] = tok.hex ? hexCell(tok.hex, static_cast<uint8_t>(done + i)) : tok.value;
      sink_->segment(static_cast<uint16_t>(row), at, buf, n);
      at = static_cast<uint16_t>(at + n);
      done = static_cast<uint16_t>(done + n);
    }
  }
  return true;
}

}  // namespace uv
