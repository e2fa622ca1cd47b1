// The DOSE: report line: `DOSE:stop=<n> prog=<p> exp=<e> on=<t0>,<t1>,<t2>,<t3>[ plan=...][ cut=1][ again=1]`.
#include "dialect_dose.h"

#include <string.h>

#include "progmem.h"
#include "text_scan.h"

namespace uv {

namespace {

// `word` (a flash literal) then a number, from p; nullptr if either is not there.
const char* scanKey(const char* p, const char* end, const char* word, uint8_t digits, uint32_t limit, uint32_t& out) {
  const size_t n = uvStrlenP(word);
  if (static_cast<size_t>(end - p) < n || uvMemcmpP(p, word, n) != 0) return nullptr;
  return scanUnsigned(p + n, end, digits, limit, out);
}

const char* scanFour(const char* p, const char* end, const char* word, uint32_t out[4]) {
  for (uint8_t i = 0; i < 4 && p; i++) {
    p = i ? (p < end && *p == ',' ? scanUnsigned(p + 1, end, 10, 0xFFFFFFFFu, out[i]) : nullptr)
          : scanKey(p, end, word, 10, 0xFFFFFFFFu, out[i]);
  }
  return p;
}

bool flag(const char*& p, const char* end, const char* word) {
  const size_t n = uvStrlenP(word);
  if (static_cast<size_t>(end - p) < n || uvMemcmpP(p, word, n) != 0) return false;
  p += n;
  return true;
}

struct Out {
  char* buf;
  size_t size, n;
  void put(const char* s, size_t k) {
    if (n + k < size) memcpy(buf + n, s, k);
    n += k;
  }
  void word(const char* flash) {
    const size_t k = uvStrlenP(flash);
    if (n + k < size) uvMemcpyP(buf + n, flash, k);
    n += k;
  }
  void num(uint32_t v) {
    char t[11];
    put(t, putUnsigned(v, t));
  }
  void four(const char* flash, const uint32_t v[4]) {
    word(flash);
    for (uint8_t i = 0; i < 4; i++) {
      if (i) put(",", 1);
      num(v[i]);
    }
  }
};

}  // namespace

bool parseDoseReport(const char* p, const char* end, DoseReport& d) {
  uint32_t program = 0;
  d = DoseReport{};
  p = scanKey(p, end, UV_P("stop="), 10, 0xFFFFFFFFu, d.stop);
  if (p) p = scanKey(p, end, UV_P(" prog="), 5, 0xFFFF, program);
  if (p) p = scanKey(p, end, UV_P(" exp="), 10, 0xFFFFFFFFu, d.exposure);
  if (!p || d.exposure == 0) return false;  // no record is numbered 0 (nano.md "O")
  d.program = static_cast<uint16_t>(program);
  p = scanFour(p, end, UV_P(" on="), d.onUs);
  if (!p) return false;
  if (const char* q = scanFour(p, end, UV_P(" plan="), d.planUs)) {
    d.hasPlan = true;
    p = q;
  }
  d.cut = flag(p, end, UV_P(" cut=1"));
  d.again = flag(p, end, UV_P(" again=1"));
  return p == end;
}

size_t formatDoseReport(const DoseReport& d, char* out, size_t size) {
  Out o{out, size, 0};
  o.word(UV_P("DOSE:stop="));
  o.num(d.stop);
  o.word(UV_P(" prog="));
  o.num(d.program);
  o.word(UV_P(" exp="));
  o.num(d.exposure);
  o.four(UV_P(" on="), d.onUs);
  if (d.hasPlan) o.four(UV_P(" plan="), d.planUs);
  if (d.cut) o.word(UV_P(" cut=1"));
  if (d.again) o.word(UV_P(" again=1"));
  if (o.n >= size) return 0;
  out[o.n] = '\0';
  return o.n;
}

}  // namespace uv
