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

// Who may drive the machine (protocol/esp.md "Who may drive it"). A page on any other site can
// make the user's browser send a request to the hub: a POST whose type needs no preflight
// (text/plain), or a WebSocket, which has no preflight at all. The browser always names that
// page's origin (`Origin`), so a request that names one must come from the hub itself: the origin's
// host and port equal to the request's Host, and that Host one of the hub's own names (its
// addresses, `uvprinter.local`; a rebound DNS name is not). A request without Origin is not
// a browser's cross-site request (curl, OctoPrint-like tools) and goes ahead. 403 otherwise.
HttpError originError(const char* origin, const char* host, const char* apIp, const char* mdnsName);
constexpr const char* kForeignOriginCode = "foreign_origin";

// A body that is not JSON is refused before it is read: 415. A text/plain body is what a foreign
// page may send without a preflight; POST /print and POST /wifi take application/json only.
HttpError jsonBodyError(const char* contentType);

// A slow client must not hold the hub: its one spool, or one of its few sockets.
// The request line and headers are at most kHeaderBytesMax bytes; a request is whole within
// kRequestDeadlineMs of its first byte (1.2 MB at 20 KB/s; Wi-Fi carries ten times that), or its
// connection is closed and nothing of it kept.
constexpr uint16_t kHeaderBytesMax = 4096;
constexpr uint32_t kRequestDeadlineMs = 60000;
// True once a request that began at startMs has run out of time at nowMs (wraps with millis()).
inline bool pastDeadline(uint32_t startMs, uint32_t nowMs) { return nowMs - startMs > kRequestDeadlineMs; }

// A connection's request line and headers, counted as their bytes arrive, before the web library
// parses them (ESPAsyncWebServer keeps a header line whole, however long it grows, until its heap
// runs short). take() is false once they are over kHeaderBytesMax without the blank line that
// ends them, or past the deadline: the connection is to be cut. From the blank line on, every
// byte is the body's, and passes.
class HeaderBudget {
 public:
  explicit HeaderBudget(uint32_t startMs) : startMs_(startMs) {}
  bool take(const uint8_t* data, size_t len, uint32_t nowMs) {
    if (done_) return true;
    if (pastDeadline(startMs_, nowMs)) return false;
    for (size_t i = 0; i < len && !done_; i++) {
      if (++bytes_ > kHeaderBytesMax) return false;
      if (data[i] == '\n') {
        done_ = lineBytes_ == 0;  // an empty line (CR LF, or LF alone) ends the headers
        lineBytes_ = 0;
      } else if (data[i] != '\r') {
        lineBytes_++;
      }
    }
    return true;
  }
  bool done() const { return done_; }

 private:
  uint32_t startMs_;
  uint16_t bytes_ = 0, lineBytes_ = 0;
  bool done_ = false;
};

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
