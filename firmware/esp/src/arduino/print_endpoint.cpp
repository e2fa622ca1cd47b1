// POST /print's body spooled to LittleFS, checked in loop() steps by PrintIntake, answered, then
// uploaded; DELETE /print and GET /status.
#include "print_endpoint.h"

#include <ArduinoJson.h>
#include <LittleFS.h>

#include "file_body.h"
#include "http_rules.h"
#include "json_view.h"
#include "print_intake.h"

namespace uv {
namespace esp {

namespace {

const char kSpool[] = "/job.json";  // the body: the upload is made from it again on a retry
const char kJobIdFile[] = "/jobid";

Bridge* bridge = nullptr;
void (*service)() = nullptr;
void serviceHook() {
  if (service) service();
}
FileBody body(LittleFS, kSpool, serviceHook);

// The header: the whole body through ArduinoJson with gridData's contents filtered out, which
// also checks the body's syntax, in at most 8 KB of heap.
struct HeaderParse {
  template <class F>
  int operator()(FileBody& b, F use) const {
    if (!b.rewind()) return 400;
    CappedAllocator cap(8192);
    JsonDocument doc(&cap);
    JsonDocument filter;
    filter["*"] = true;
    filter["gridData"] = false;
    DeserializationError err = deserializeJson(doc, b, DeserializationOption::Filter(filter));
    if (err == DeserializationError::NoMemory) return 413;
    if (err) return 400;
    use(JsonView{doc.as<JsonVariantConst>()});
    return 0;
  }
};

PrintIntake<FileBody, HeaderParse>* intake = nullptr;
AsyncWebServerRequest* waiting = nullptr;  // the POST whose answer is being worked out
bool receiving = false;
fs::File spool;
bool spoolFailed = false;
char reply[LiveChannel::kMaxMessage];

void sendError(AsyncWebServerRequest* r, uint16_t status, const char* code, const char* message) {
  JsonWriter w(reply, sizeof reply);
  writeError(w, code, message);
  r->send(status, "application/json", w.text());
}

uint32_t nextJobId() {
  uint32_t id = 0;
  fs::File f = LittleFS.open(kJobIdFile, "r");
  if (f) {
    id = static_cast<uint32_t>(f.parseInt());
    f.close();
  }
  id = id % 99999 + 1;  // JOB<id>.UVJ stays an 8.3 name
  f = LittleFS.open(kJobIdFile, "w");
  if (f) {
    f.print(id);
    f.close();
  }
  return id;
}

void onBody(AsyncWebServerRequest* r, uint8_t* data, size_t len, size_t index, size_t total) {
  if (index == 0) {
    // A chunked body has no length to judge it by before it is read: 411.
    bool hasLength = !r->hasHeader("Transfer-Encoding");
    HttpError e = admitPrintRequest(r->contentType().c_str(), hasLength, static_cast<uint32_t>(total), *bridge, millis());
    if (e.status) {  // answered once the body has gone by; none of it is kept
      r->_tempObject = malloc(sizeof(HttpError));  // the library frees it with the request
      if (r->_tempObject) memcpy(r->_tempObject, &e, sizeof e);
      return;
    }
    spool = LittleFS.open(kSpool, "w");
    spoolFailed = !spool;
    receiving = true;
    waiting = r;
    r->onDisconnect([] {
      // A client gone before its answer: a body cut short is dropped, and a job nobody was told
      // about does not start. Either way the Mega is free again.
      waiting = nullptr;
      if (receiving) {
        receiving = false;
        spool.close();
        bridge->release();
      } else if (intake->busy()) {
        intake->cancel();
      }
    });
  }
  if (r != waiting || !receiving) return;
  if (!spoolFailed && spool.write(data, len) != len) spoolFailed = true;
}

void onPost(AsyncWebServerRequest* r) {
  if (r->_tempObject) {
    const HttpError* e = static_cast<const HttpError*>(r->_tempObject);
    return sendError(r, e->status, e->code, e->message);
  }
  if (r != waiting || !receiving) {  // no body at all
    HttpError e = admitPrintRequest(r->contentType().c_str(), true, 0, *bridge, millis());
    if (e.status) return sendError(r, e.status, e.code, e.message);
    bridge->release();
    return sendError(r, 400, "bad_json", "the body is empty");
  }
  receiving = false;
  spool.close();
  if (spoolFailed) {
    bridge->release();
    waiting = nullptr;
    return sendError(r, 503, "spool_failed", "the ESP could not store the job; its flash may be full");
  }
  intake->begin();  // loop() takes it from here
}

void onDelete(AsyncWebServerRequest* r) {
  JsonWriter w(reply, sizeof reply);
  w.beginObject().key("job").beginObject().key("state").string("aborted").endObject().endObject();
  if (intake->busy()) {
    intake->cancel();
    if (waiting) waiting->send(intake->status(), "application/json", intake->response());
    waiting = nullptr;
    return r->send(200, "application/json", w.text());
  }
  if (!bridge->cancel()) return sendError(r, 409, "busy", "nothing to cancel");
  r->send(200, "application/json", w.text());
}

void onStatus(AsyncWebServerRequest* r) {
  JsonWriter w(reply, sizeof reply);
  bridge->writeStatus(w, millis());
  r->send(200, "application/json", w.text());
}

}  // namespace

void beginPrintEndpoint(AsyncWebServer& server, Bridge& b, void (*serviceFn)()) {
  bridge = &b;
  service = serviceFn;
  static PrintIntake<FileBody, HeaderParse> theIntake(body, b, HeaderParse{});
  intake = &theIntake;
  server.on("/print", HTTP_POST, onPost, nullptr, onBody);
  server.on("/print", HTTP_DELETE, onDelete);
  server.on("/status", HTTP_GET, onStatus);
}

void pollPrintEndpoint() {
  if (!intake->busy()) return;
  Intake outcome = intake->step(nextJobId);
  if (outcome == Intake::Working) return;
  if (waiting) waiting->send(intake->status(), "application/json", intake->response());
  waiting = nullptr;
}

}  // namespace esp
}  // namespace uv
