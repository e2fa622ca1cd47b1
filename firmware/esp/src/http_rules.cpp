// The ESP's HTTP decisions (protocol/esp.md), kept apart from the web server.
#include "http_rules.h"

#include <stdio.h>
#include <string.h>
#include <strings.h>

namespace uv {
namespace esp {

HttpError jsonBodyError(const char* contentType) {
  size_t n = strlen("application/json");
  if (!contentType || strncasecmp(contentType, "application/json", n) != 0 || (contentType[n] && contentType[n] != ';' && contentType[n] != ' ')) {
    return {415, "unsupported_media_type", "send the body as application/json"};
  }
  return {0, "", ""};
}

namespace {
// "host[:port]" without a default ":80", lower case, into out; false if it does not fit.
bool hostPort(const char* from, size_t n, char* out, size_t size) {
  if (n >= size) return false;
  for (size_t i = 0; i < n; i++) out[i] = static_cast<char>(from[i] >= 'A' && from[i] <= 'Z' ? from[i] + 32 : from[i]);
  out[n] = 0;
  if (n > 3 && strcmp(out + n - 3, ":80") == 0) out[n - 3] = 0;
  return true;
}
}  // namespace

HttpError originError(const char* origin, const char* host, const char* apIp, const char* mdnsName) {
  if (!origin || !origin[0]) return {0, "", ""};  // not a browser's cross-site request
  const HttpError refused{403, kForeignOriginCode, "only the hub's own pages may drive the printer"};
  static const char kScheme[] = "http://";  // the hub serves plain HTTP; "null" and https:// are foreign
  if (strncasecmp(origin, kScheme, sizeof kScheme - 1) != 0 || !host || !host[0]) return refused;
  const char* from = origin + sizeof kScheme - 1;
  char o[72], h[72];
  if (!hostPort(from, strcspn(from, "/"), o, sizeof o) || !hostPort(host, strlen(host), h, sizeof h)) return refused;
  if (strcmp(o, h) != 0 || isForeignHost(h, apIp, mdnsName)) return refused;
  return {0, "", ""};
}

HttpError printHeaderError(const char* contentType, bool hasLength, uint32_t contentLength) {
  HttpError type = jsonBodyError(contentType);
  if (type.status) return {415, "unsupported_media_type", "send the job as application/json"};
  if (!hasLength) return {411, "length_required", "send a Content-Length"};
  RequestError e{};
  if (bodyTooLarge(contentLength, e)) return {413, "too_large", "the body is over 1200000 bytes; send larger jobs over USB"};
  return {0, "", ""};
}

HttpError admissionError(Admission a) {
  switch (a) {
    case Admission::Busy: return {409, "busy", "a job is uploading or running"};
    case Admission::MegaOffline: return {503, "mega_offline", "the Mega does not answer"};
    default: return {0, "", ""};
  }
}

HttpError admitPrintRequest(const char* contentType, bool hasLength, uint32_t contentLength, Bridge& bridge, uint32_t nowMs) {
  HttpError e = printHeaderError(contentType, hasLength, contentLength);
  return e.status ? e : admissionError(bridge.admitPrint(nowMs));
}

HttpError methodNotAllowed(const char* path, Method m) {
  bool ok = true;
  if (strcmp(path, "/print") == 0) ok = m == Method::Post || m == Method::Delete;
  else if (strcmp(path, "/status") == 0) ok = m == Method::Get;
  else if (strcmp(path, "/wifi") == 0) ok = m == Method::Get || m == Method::Post;
  else ok = m == Method::Get;
  if (ok) return {0, "", ""};
  return {405, "method_not_allowed", "wrong method for this path"};
}

void writeError(JsonWriter& w, const char* code, const char* message, const char* path) {
  w.beginObject().key("error").beginObject().key("code").string(code).key("message").string(message);
  // Every bad_job names its field; "" is the whole body (protocol/esp.md "Errors").
  if ((path && path[0]) || strcmp(code, "bad_job") == 0) w.key("path").string(path ? path : "");
  w.endObject().endObject();
}

const char* contentType(const char* path) {
  static const struct {
    const char* ext;
    const char* type;
  } kTypes[] = {
      {".html", "text/html; charset=utf-8"}, {".js", "text/javascript"},       {".css", "text/css"},
      {".svg", "image/svg+xml"},             {".png", "image/png"},            {".ico", "image/x-icon"},
      {".json", "application/json"},         {".webmanifest", "application/manifest+json"},
      {".woff2", "font/woff2"},              {".txt", "text/plain; charset=utf-8"},
  };
  size_t n = strlen(path);
  for (const auto& t : kTypes) {
    size_t k = strlen(t.ext);
    if (n >= k && strcasecmp(path + n - k, t.ext) == 0) return t.type;
  }
  return "application/octet-stream";
}

const char* cacheControl(const char* path) {
  size_t n = strlen(path);
  auto ends = [&](const char* e) { return n >= strlen(e) && strcmp(path + n - strlen(e), e) == 0; };
  return strcmp(path, "/index.html") == 0 || ends(".webmanifest") || ends("/sw.js") ? "no-cache" : "public, max-age=31536000, immutable";
}

void gzipEtag(const uint8_t t[8], char out[24]) {
  uint32_t crc = t[0] | t[1] << 8 | t[2] << 16 | static_cast<uint32_t>(t[3]) << 24;
  uint32_t size = t[4] | t[5] << 8 | t[6] << 16 | static_cast<uint32_t>(t[7]) << 24;
  snprintf(out, 24, "\"%08lx-%lx\"", static_cast<unsigned long>(crc), static_cast<unsigned long>(size));
}

bool isForeignHost(const char* host, const char* apIp, const char* mdnsName) {
  if (!host || !host[0]) return false;
  char name[64];
  snprintf(name, sizeof name, "%s", host);
  char* colon = strchr(name, ':');  // drop a port
  if (colon) *colon = 0;
  if (strcmp(name, apIp) == 0) return false;
  char local[48];
  snprintf(local, sizeof local, "%s.local", mdnsName);
  if (strcasecmp(name, local) == 0 || strcasecmp(name, mdnsName) == 0) return false;
  // An address on a network the ESP joined is the user's own choice: any dotted IPv4 is ours.
  bool dotted = true;
  for (const char* c = name; *c; c++) dotted = dotted && ((*c >= '0' && *c <= '9') || *c == '.');
  return !dotted;
}

}  // namespace esp
}  // namespace uv
