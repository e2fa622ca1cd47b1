// The HTTP decisions of protocol/esp.md, apart from the web server: which status a request gets
// before its body is read, the JSON error body, the app's content types and ETags, and whether a
// request is a phone's captive-portal probe. Plain C++, host-tested; main's glue applies them.
#pragma once
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "bridge.h"
#include "json_writer.h"
#include "print_request.h"

namespace uv {
namespace esp {

enum class Method : uint8_t { Get, Post, Delete, Other };

// DELETE /print's answer when it cancelled something (protocol/esp.md).
constexpr const char* kCancelledJson = "{\"job\":{\"state\":\"aborted\"}}";
// What a POST /print cancelled by a DELETE is answered: 409, with this code and message.
constexpr const char* kCancelledCode = "cancelled";
constexpr const char* kCancelledMessage = "cancelled by DELETE /print";

struct HttpError {
  uint16_t status;  // 0 = go ahead
  const char* code;
  const char* message;
};

// POST /print, from its headers alone: 415, 413 (from Content-Length, before a byte is read),
// 409, 503; or go ahead (then the Mega is held for this job until it starts or is refused).
HttpError admitPrintRequest(const char* contentType, bool hasLength, uint32_t contentLength, Bridge& bridge, uint32_t nowMs);
// Its two halves, for the ESP, where the bridge is another task's: what the headers alone say
// (415, 411, 413), and what an admission of the Mega means for the request (409, 503).
HttpError printHeaderError(const char* contentType, bool hasLength, uint32_t contentLength);
HttpError admissionError(Admission a);

// A method the path does not take.
HttpError methodNotAllowed(const char* path, Method m);

// {"error": {"code", "message", "path"?}}: path when given, and always for bad_job.
void writeError(JsonWriter& w, const char* code, const char* message, const char* path = "");

// Room for writeError() of any RequestError: each byte of its path and message may escape to six
// (\u00XX), plus a code of up to 32 characters and the punctuation.
constexpr uint16_t kErrorJsonBytes = 96 + 6 * (sizeof(RequestError::path) - 1) + 6 * (sizeof(RequestError::message) - 1);

// The content type of an app file by its name (without .gz).
const char* contentType(const char* path);

enum class AppFile : uint8_t { Found, NotFound, NoApp };

// Which of the app's gzipped files answers a GET for `url` (its query ignored): out receives the
// path served, whose `<path>.gz` the caller opens. A folder is its index.html; a path of the app
// itself (no extension) opens the app's index.html; a missing file, or one outside the app, is
// NotFound; NoApp when the app is not on the flash at all. `exists(path)` says if <path>.gz is there.
template <class Exists>
AppFile appFile(const char* url, char* out, size_t size, Exists exists) {
  size_t n = strcspn(url, "?");
  if (n + sizeof "index.html" > size || n == 0 || url[0] != '/') return AppFile::NotFound;
  memcpy(out, url, n);
  out[n] = 0;
  if (strstr(out, "..")) return AppFile::NotFound;
  if (out[n - 1] == '/') strcat(out, "index.html");
  if (exists(static_cast<const char*>(out))) return AppFile::Found;
  const char* dot = strrchr(out, '.');
  if (dot && dot > strrchr(out, '/')) return AppFile::NotFound;
  snprintf(out, size, "/index.html");
  return exists(static_cast<const char*>(out)) ? AppFile::Found : AppFile::NoApp;
}

// index.html (and the manifest and service worker) are checked every time; the hashed assets they
// name never change.
const char* cacheControl(const char* path);

// A strong ETag for a gzip file from its last 8 bytes (CRC-32 and length of the content), so
// the ESP need not hash the file: `"<crc>-<size>"`.
void gzipEtag(const uint8_t trailer[8], char out[24]);

// True when a request for `host` is not for the ESP itself: a phone checking for a captive
// portal, or a typed address, is sent to the app (302 to http://<ip>/).
bool isForeignHost(const char* host, const char* apIp, const char* mdnsName);

}  // namespace esp
}  // namespace uv
