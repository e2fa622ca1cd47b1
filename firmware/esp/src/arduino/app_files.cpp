// Serves the gzipped app from LittleFS with ETags, and sends captive-portal probes to it. The files
// are read only while loop() is outside LittleFS (flash_gate.h): a request that comes while it is
// inside is answered 503 flash_busy, and a file being sent waits for the connection's next poll.
#include "app_files.h"

#include <LittleFS.h>

#include "flash_guard.h"
#include "http_rules.h"
#include "network.h"

namespace uv {
namespace esp {

namespace {

void sendError(AsyncWebServerRequest* r, uint16_t status, const char* code, const char* message) {
  char buf[160];
  JsonWriter w(buf, sizeof buf);
  writeError(w, code, message);
  r->send(status, "application/json", w.text());
}

Method methodOf(AsyncWebServerRequest* r) {
  if (r->method() == HTTP_GET || r->method() == HTTP_HEAD) return Method::Get;
  if (r->method() == HTTP_POST) return Method::Post;
  if (r->method() == HTTP_DELETE) return Method::Delete;
  return Method::Other;
}

void onOther(AsyncWebServerRequest* r) {
  if (isForeignHost(r->host().c_str(), apAddress(), kMdnsName)) {
    char to[40];
    snprintf(to, sizeof to, "http://%s/", apAddress());
    return r->redirect(to);
  }
  HttpError m = methodNotAllowed(r->url().c_str(), methodOf(r));
  if (m.status) return sendError(r, m.status, m.code, m.message);
  if (flashBusy()) return sendFlashBusy(r);
  char path[96];
  AppFile found = appFile(r->url().c_str(), path, sizeof path, [](const char* p) { return LittleFS.exists(String("/www") + p + ".gz"); });
  if (found == AppFile::NotFound) return sendError(r, 404, "not_found", "no such path");
  if (found == AppFile::NoApp) return sendError(r, 404, "not_found", "the app is not on this ESP: npm run build:esp, then uploadfs");
  String file = String("/www") + path;
  char etag[24] = "";
  String gz = file + ".gz";
  fs::File f = LittleFS.open(gz, "r");
  size_t size = f ? f.size() : 0;
  if (f && size >= 8 && f.seek(size - 8)) {
    uint8_t trailer[8];
    if (f.read(trailer, 8) == 8) gzipEtag(trailer, etag);
  }
  if (f) f.close();
  if (!size) return sendError(r, 404, "not_found", "no such path");
  if (etag[0] && r->hasHeader("If-None-Match") && r->getHeader("If-None-Match")->value() == etag) {
    AsyncWebServerResponse* notModified = r->beginResponse(304);
    notModified->addHeader("ETag", etag);
    return r->send(notModified);
  }
  // Sent a part at a time from the network callbacks as the client acknowledges: each part opens
  // the file, so nothing of LittleFS is held between two callbacks, and a part asked for while loop()
  // is inside LittleFS is asked again at the connection's next poll (the library's RESPONSE_TRY_AGAIN).
  AsyncWebServerResponse* res = r->beginResponse(contentType(path), size, [gz](uint8_t* out, size_t max, size_t index) -> size_t {
    if (flashBusy()) return RESPONSE_TRY_AGAIN;
    fs::File part = LittleFS.open(gz, "r");
    if (!part || !part.seek(index)) return 0;  // gone meanwhile: the response ends short, the client sees it cut
    size_t n = part.read(out, max);
    part.close();
    return n;
  });
  res->addHeader("Content-Encoding", "gzip");
  if (etag[0]) res->addHeader("ETag", etag);
  res->addHeader("Cache-Control", cacheControl(path));
  r->send(res);
}

}  // namespace

void beginAppFiles(AsyncWebServer& server) { server.onNotFound(onOther); }

}  // namespace esp
}  // namespace uv
