// The ESP's FlashGate and the answer of a request that finds it held.
#include "flash_guard.h"

#include "http_rules.h"

namespace uv {
namespace esp {

FlashGate fileSystemGate;

void sendFlashBusy(AsyncWebServerRequest* r) {
  char buf[128];
  JsonWriter w(buf, sizeof buf);
  writeError(w, kFlashBusyCode, kFlashBusyMessage);
  AsyncWebServerResponse* res = r->beginResponse(kFlashBusyStatus, "application/json", w.text());
  res->addHeader("Retry-After", kFlashRetryAfter);
  r->send(res);
}

}  // namespace esp
}  // namespace uv
