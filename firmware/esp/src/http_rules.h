// The HTTP decisions of protocol/esp.md, apart from the web server: which status a request gets
// before its body is read, the JSON error body, the app's content types and ETags, and whether a
// request is a phone's captive-portal probe. Plain C++, host-tested; main's glue applies them.
#pragma once
#include <stdint.h>

#include "bridge.h"
#include "json_writer.h"
#include "print_request.h"

namespace uv {
namespace esp {

enum class Method : uint8_t { Get, Post, Delete, Other };

struct HttpError {
  uint16_t status;  // 0 = go ahead
  const char* code;
  const char* message;
};

// POST /print, from its headers alone: 415, 413 (from Content-Length, before a byte is read),
// 409, 503; or go ahead (then the Mega is held for this job until it starts or is refused).
HttpError admitPrintRequest(const char* contentType, bool hasLength, uint32_t contentLength, Bridge& bridge, uint32_t nowMs);

// A method the path does not take.
HttpError methodNotAllowed(const char* path, Method m);

// {"error": {"code", "message", "path"?}}
void writeError(JsonWriter& w, const char* code, const char* message, const char* path = "");

// The content type of an app file by its name (without .gz).
const char* contentType(const char* path);

// A strong ETag for a gzip file from its last 8 bytes (CRC-32 and length of the content), so
// the ESP need not hash the file: `"<crc>-<size>"`.
void gzipEtag(const uint8_t trailer[8], char out[24]);

// True when a request for `host` is not for the ESP itself: a phone checking for a captive
// portal, or a typed address, is sent to the app (302 to http://<ip>/).
bool isForeignHost(const char* host, const char* apIp, const char* mdnsName);

}  // namespace esp
}  // namespace uv
