// Validates a POST /print body (protocol/esp.md, print-job.schema.json) into a JobHeader and rows,
// and whether to run the job paced (a flag beside the job, never part of its text).
// A template over a small JSON view, so the same code runs on ArduinoJson (ESP) and nlohmann (host tests).
// The header is checked first, then each row as it streams in; only one row is ever in RAM.
//
// A view J provides: isObject() isArray() isString() isInteger() isBoolean() integer() boolean() string() size()
// element(i) has(key) member(key) and forEachKey(f) with f(const char*) returning false to stop.
#pragma once
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "job_types.h"

namespace uv {
namespace esp {

constexpr uint32_t kMaxBody = 1200000;
constexpr uint32_t kMaxCells = 262144;

// Where the rows walker (grid_rows.h) found gridData: the header parse leaves it out.
struct GridDataShape {
  bool present = false;
  bool isArray = false;
};

struct RequestError {
  uint16_t status;   // 0 = fine
  const char* code;  // "bad_json", "bad_job", "too_large"
  char path[48];     // JSON Pointer of the field at fault ("" = the whole body)
  char message[64];
};

// Content-Length is checked before a byte of the body is read.
inline bool bodyTooLarge(uint32_t contentLength, RequestError& e) {
  if (contentLength <= kMaxBody) return false;
  e = {413, "too_large", "", ""};
  snprintf(e.message, sizeof e.message, "body over %lu bytes", static_cast<unsigned long>(kMaxBody));
  return true;
}

namespace detail {

inline bool fail(RequestError& e, const char* path, const char* message, uint16_t status = 400) {
  e.status = status;
  e.code = status == 413 ? "too_large" : "bad_job";
  snprintf(e.path, sizeof e.path, "%s", path);
  snprintf(e.message, sizeof e.message, "%s", message);
  return false;
}

inline void join(char* out, size_t size, const char* base, const char* key) { snprintf(out, size, "%s/%s", base, key); }
inline void join(char* out, size_t size, const char* base, unsigned long index) { snprintf(out, size, "%s/%lu", base, index); }

template <class J>
bool object(const J& v, const char* path, const char* const* keys, uint8_t nKeys, const char* const* required, uint8_t nRequired,
            RequestError& e) {
  if (!v.isObject()) return fail(e, path, "must be an object");
  char unknown[48] = "";
  v.forEachKey([&](const char* k) {
    for (uint8_t i = 0; i < nKeys; i++)
      if (strcmp(k, keys[i]) == 0) return true;
    join(unknown, sizeof unknown, path, k);
    return false;
  });
  if (unknown[0]) return fail(e, unknown, "unknown field");
  for (uint8_t i = 0; i < nRequired; i++) {
    if (!v.has(required[i])) {
      char p[48];
      join(p, sizeof p, path, required[i]);
      return fail(e, p, "missing");
    }
  }
  return true;
}

template <class J>
bool integer(const J& v, const char* path, int64_t lo, int64_t hi, int64_t& out, RequestError& e) {
  if (!v.isInteger() || v.integer() < lo || v.integer() > hi) return fail(e, path, "must be an integer in range");
  out = v.integer();
  return true;
}

template <class J, class T>
bool field(const J& parent, const char* base, const char* key, int64_t lo, int64_t hi, T& out, RequestError& e) {
  char p[48];
  join(p, sizeof p, base, key);
  int64_t v = 0;
  if (!integer(parent.member(key), p, lo, hi, v, e)) return false;
  out = static_cast<T>(v);
  return true;
}

template <class J>
bool array(const J& v, const char* path, size_t lo, size_t hi, RequestError& e) {
  if (!v.isArray() || v.size() < lo || v.size() > hi) return fail(e, path, "array of the wrong size");
  return true;
}

template <class J, class T>
bool intArray(const J& parent, const char* base, const char* key, size_t n, int64_t lo, int64_t hi, T* out, RequestError& e) {
  char p[48], q[48];
  join(p, sizeof p, base, key);
  const J a = parent.member(key);
  if (!array(a, p, n, n, e)) return false;
  for (size_t i = 0; i < n; i++) {
    join(q, sizeof q, p, static_cast<unsigned long>(i));
    int64_t v = 0;
    if (!integer(a.element(i), q, lo, hi, v, e)) return false;
    out[i] = static_cast<T>(v);
  }
  return true;
}

template <class J>
bool xy(const J& parent, const char* key, int64_t lo, int64_t hi, uint32_t* out, RequestError& e) {
  static const char* const keys[] = {"x", "y"};
  char p[48];
  join(p, sizeof p, "", key);
  const J v = parent.member(key);
  return object(v, p, keys, 2, keys, 2, e) && field(v, p, "x", lo, hi, out[0], e) && field(v, p, "y", lo, hi, out[1], e);
}

}  // namespace detail

// Everything but gridData's rows, in the order protocol/esp.md's validator uses (the vectors depend
// on it). `root` may lack gridData (the ESP filters it out of the parse); `grid` says how the rows
// walker found it. Its row count and rows are checked by grid_rows.h as they stream. `paced`: the
// body's optional "paced" (false without it), which starts the job with M24 P1 (mega.md "Pacing").
template <class J>
bool validateHeader(const J& root, GridDataShape grid, JobHeader& h, bool& paced, RequestError& e) {
  using namespace detail;
  static const char* const rootKeys[] = {"name", "grid", "pitchUm", "originUm", "dose", "leds", "thermal", "strategy", "paced", "gridData"};
  static const char* const rootRequired[] = {"grid", "pitchUm", "originUm", "dose", "leds", "strategy"};
  e = {0, "", "", ""};
  h = JobHeader{};
  paced = false;
  if (!object(root, "", rootKeys, 10, rootRequired, 6, e)) return false;
  if (!grid.present) return fail(e, "/gridData", "missing");
  if (root.has("name")) {
    const J n = root.member("name");
    bool ok = n.isString() && strlen(n.string()) >= 1 && strlen(n.string()) <= 31;
    for (const char* c = ok ? n.string() : ""; *c && ok; c++)
      ok = (*c >= 'A' && *c <= 'Z') || (*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '_' || *c == '.' || *c == '-';
    if (!ok) return fail(e, "/name", "must be 1-31 of A-Z a-z 0-9 _ . -");
  }
  static const char* const gridKeys[] = {"cols", "rows"};
  const J g = root.member("grid");
  if (!object(g, "/grid", gridKeys, 2, gridKeys, 2, e) || !field(g, "/grid", "cols", 1, kJobMaxSide, h.cols, e) ||
      !field(g, "/grid", "rows", 1, kJobMaxSide, h.rows, e)) {
    return false;
  }
  if (static_cast<uint32_t>(h.cols) * h.rows > kMaxCells) return fail(e, "/grid", "over 262144 cells; send larger jobs over USB", 413);
  if (!xy(root, "pitchUm", 1, 100000, h.pitchUm, e) || !xy(root, "originUm", 0, 10000000, h.originUm, e)) return false;

  static const char* const doseKeys[] = {"map", "level", "fullUs", "targetUJcm2", "irradianceUWcm2"};
  static const char* const doseRequired[] = {"map"};
  const J d = root.member("dose");
  if (!object(d, "/dose", doseKeys, 5, doseRequired, 1, e)) return false;
  const J map = d.member("map");
  bool threshold = map.isString() && strcmp(map.string(), "threshold") == 0;
  if (!threshold && !(map.isString() && strcmp(map.string(), "linear") == 0)) return fail(e, "/dose/map", "must be linear or threshold");
  if (threshold && !d.has("level")) return fail(e, "/dose/level", "threshold needs a level");
  if (!threshold && d.has("level")) return fail(e, "/dose/level", "linear takes no level");
  h.map = threshold ? DoseMap::Threshold : DoseMap::Linear;
  if (threshold && !field(d, "/dose", "level", 1, 255, h.level, e)) return false;
  bool hasTarget = d.has("targetUJcm2") || d.has("irradianceUWcm2");
  if (d.has("fullUs") == hasTarget) return fail(e, "/dose", "give fullUs, or targetUJcm2 with irradianceUWcm2");
  h.byTarget = hasTarget;
  if (!hasTarget) {
    if (!field(d, "/dose", "fullUs", 1, 10000000, h.fullUs, e)) return false;
  } else {
    if (!d.has("targetUJcm2")) return fail(e, "/dose/targetUJcm2", "missing");
    if (!d.has("irradianceUWcm2")) return fail(e, "/dose/irradianceUWcm2", "missing");
    if (!field(d, "/dose", "targetUJcm2", 1, 100000000, h.targetUJcm2, e) ||
        !intArray(d, "/dose", "irradianceUWcm2", 4, 1, 10000000, h.irradianceUWcm2, e)) {
      return false;
    }
  }

  static const char* const ledKeys[] = {"offsets", "gainPermille"};
  static const char* const ledRequired[] = {"offsets"};
  const J l = root.member("leds");
  if (!object(l, "/leds", ledKeys, 2, ledRequired, 1, e)) return false;
  const J offsets = l.member("offsets");
  if (!array(offsets, "/leds/offsets", 4, 4, e)) return false;
  for (size_t i = 0; i < 4; i++) {
    char p[48];
    join(p, sizeof p, "/leds/offsets", static_cast<unsigned long>(i));
    const J pair = offsets.element(i);
    if (!array(pair, p, 2, 2, e)) return false;
    for (size_t k = 0; k < 2; k++) {
      char q[48];
      int64_t v = 0;
      join(q, sizeof q, p, static_cast<unsigned long>(k));
      if (!integer(pair.element(k), q, -4096, 4096, v, e)) return false;
      h.offsets[i][k] = static_cast<int16_t>(v);
    }
  }
  for (uint8_t i = 0; i < 4; i++) h.gainPermille[i] = 1000;
  if (l.has("gainPermille") && !intArray(l, "/leds", "gainPermille", 4, 1, 10000, h.gainPermille, e)) return false;

  h.thermalCoeff = 0;
  h.thermalRefDeciC = 250;
  if (root.has("thermal")) {
    static const char* const tKeys[] = {"coeffCentiPctPerC", "refDeciC"};
    const J t = root.member("thermal");
    if (!object(t, "/thermal", tKeys, 2, tKeys, 2, e) || !field(t, "/thermal", "coeffCentiPctPerC", -1000, 1000, h.thermalCoeff, e) ||
        !field(t, "/thermal", "refDeciC", -400, 1250, h.thermalRefDeciC, e)) {
      return false;
    }
  }

  static const char* const sKeys[] = {"name", "seed"};
  static const char* const sRequired[] = {"name"};
  const J s = root.member("strategy");
  if (!object(s, "/strategy", sKeys, 2, sRequired, 1, e)) return false;
  const J name = s.member("name");
  int8_t strategy = -1;
  for (uint8_t i = 0; i < kStrategyCount && name.isString(); i++)
    if (strcmp(name.string(), strategyName(static_cast<Strategy>(i))) == 0) strategy = static_cast<int8_t>(i);
  if (strategy < 0) return fail(e, "/strategy/name", "must be raster, serpentine, shortest, random or scan");
  h.strategy = static_cast<Strategy>(strategy);
  h.seed = 0;
  if (s.has("seed") && !field(s, "/strategy", "seed", 0, 4294967295LL, h.seed, e)) return false;

  if (root.has("paced")) {
    const J p = root.member("paced");
    if (!p.isBoolean()) return fail(e, "/paced", "must be true or false");
    paced = p.boolean();
  }

  if (!grid.isArray) return fail(e, "/gridData", "array of the wrong size");
  return true;
}

}  // namespace esp
}  // namespace uv
