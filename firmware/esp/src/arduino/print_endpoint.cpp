// POST /print's body spooled to LittleFS, checked in loop() steps by PrintIntake, answered, then
// uploaded; DELETE /print and GET /status. Requests that need the bridge are paused and handed to
// loop(), which answers them through the library's request continuation.
//
// Who owns what (hub_lock.h says how each chip keeps the tasks apart):
// - the network task: the body being received (`receiving`, `spool`, `spoolFailed`), and a
//   request until it is paused and handed over;
// - loop(): the bridge, the intake, the request whose answer the intake is working out
//   (`waiting`), the job-id file;
// - between them: `handed`, the queue loop() empties each pass; and the bridge's admission of a
//   POST (admitPrint, release), which the network task makes under HubLock.
// A paused request is only ever reached through its AsyncWebServerRequestPtr, a weak pointer the
// library empties when the client goes: nothing is answered twice, and nothing dangles.
#include "print_endpoint.h"

#include <ArduinoJson.h>
#include <LittleFS.h>

#include "file_body.h"
#include "hand_over.h"
#include "http_rules.h"
#include "hub_lock.h"
#include "json_view.h"
#include "print_intake.h"

namespace uv {
namespace esp {

HubLock hubLock;

namespace {

const char kSpool[] = "/job.json";  // the body: the upload is made from it again on a retry
const char kJobIdFile[] = "/jobid";
constexpr uint8_t kHanded = 8;  // requests waiting for loop(); more are answered 503 at once

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

// --- handed from the network task to loop() ---
enum class Ask : uint8_t { None, Status, Cancel, CheckBody };
struct Handed {
  Ask ask = Ask::None;
  AsyncWebServerRequestPtr request;
  bool spoolFailed = false;  // CheckBody: the body could not be stored whole
};
HandOver<Handed, kHanded, EntryLock> handed;

// --- the network task's ---
AsyncWebServerRequest* receiving = nullptr;  // the POST whose body is arriving (identity only)
fs::File spool;
bool spoolFailed = false;
char netReply[kErrorJsonBytes];  // answers written on the network task (off its small stack)

// --- loop()'s ---
PrintIntake<FileBody, HeaderParse>* intake = nullptr;
AsyncWebServerRequestPtr waiting;  // the POST whose answer the intake is working out
char loopReply[kErrorJsonBytes > 2048 ? kErrorJsonBytes : 2048];  // a status, or any error

void sendJson(AsyncWebServerRequest* r, uint16_t status, const JsonWriter& w) {
  if (w.ok()) r->send(status, "application/json", w.text());
  else r->send(500, "text/plain", "the answer did not fit");  // whole or nothing: never cut-off JSON
}

void sendError(AsyncWebServerRequest* r, char* buf, uint16_t size, uint16_t status, const char* code, const char* message) {
  JsonWriter w(buf, size);
  writeError(w, code, message);
  sendJson(r, status, w);
}

// Network task: hands a request to loop(), paused so the library sends nothing meanwhile; with
// no room it is answered at once.
void handOver(AsyncWebServerRequest* r, Ask ask, bool failed = false) {
  Handed h;
  h.ask = ask;
  h.request = r->pause();
  h.spoolFailed = failed;
  if (handed.put(std::move(h))) return;
  if (ask == Ask::CheckBody) {
    HubGuard g;
    bridge->release();
  }
  sendError(r, netReply, sizeof netReply, 503, "overloaded", "too many requests are waiting for the ESP; try again");
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

// Network task: the POST's headers are judged before a byte of its body is kept.
void onBody(AsyncWebServerRequest* r, uint8_t* data, size_t len, size_t index, size_t total) {
  if (index == 0) {
    // A chunked body has no length to judge it by before it is read: 411.
    bool hasLength = !r->hasHeader("Transfer-Encoding");
    HttpError e;
    {
      HubGuard g;
      e = admitPrintRequest(r->contentType().c_str(), hasLength, static_cast<uint32_t>(total), *bridge, millis());
    }
    if (e.status) {  // answered once the body has gone by; none of it is kept
      r->_tempObject = malloc(sizeof(HttpError));  // the library frees it with the request
      if (r->_tempObject) memcpy(r->_tempObject, &e, sizeof e);
      return;
    }
    spool = LittleFS.open(kSpool, "w");
    spoolFailed = !spool;
    receiving = r;
    r->onDisconnect([r] {
      // A client gone before its body was whole: what came is dropped and the Mega is free again.
      // (Gone later, loop() finds its request pointer empty and cancels the check.)
      if (r != receiving) return;
      receiving = nullptr;
      spool.close();
      HubGuard g;
      bridge->release();
    });
  }
  if (r != receiving) return;
  if (!spoolFailed && spool.write(data, len) != len) spoolFailed = true;
}

// Network task: the whole request is in.
void onPost(AsyncWebServerRequest* r) {
  if (r->_tempObject) {
    const HttpError* e = static_cast<const HttpError*>(r->_tempObject);
    return sendError(r, netReply, sizeof netReply, e->status, e->code, e->message);
  }
  if (r != receiving) {  // no body at all
    HttpError e;
    {
      HubGuard g;
      e = admitPrintRequest(r->contentType().c_str(), true, 0, *bridge, millis());
      if (!e.status) bridge->release();
    }
    if (e.status) return sendError(r, netReply, sizeof netReply, e.status, e.code, e.message);
    return sendError(r, netReply, sizeof netReply, 400, "bad_json", "the body is empty");
  }
  receiving = nullptr;
  spool.close();
  handOver(r, Ask::CheckBody, spoolFailed);  // loop() checks it and answers
}

void onDelete(AsyncWebServerRequest* r) { handOver(r, Ask::Cancel); }

void onStatus(AsyncWebServerRequest* r) { handOver(r, Ask::Status); }

// --- loop() ---

void answer(const AsyncWebServerRequestPtr& to, uint16_t status, const char* json) {
  if (auto r = to.lock()) r->send(status, "application/json", json);  // gone: nobody to tell
}

void serve(Handed& h) {
  JsonWriter w(loopReply, sizeof loopReply);
  switch (h.ask) {
    case Ask::Status:
      bridge->writeStatus(w, millis());
      if (auto r = h.request.lock()) sendJson(r.get(), 200, w);
      return;
    case Ask::Cancel:
      w.beginObject().key("job").beginObject().key("state").string("aborted").endObject().endObject();
      if (intake->busy()) {
        intake->cancel();
        answer(waiting, intake->status(), intake->response());
        waiting.reset();
      } else if (!bridge->cancel()) {
        w = JsonWriter(loopReply, sizeof loopReply);
        writeError(w, "busy", "nothing to cancel");
        if (auto r = h.request.lock()) sendJson(r.get(), 409, w);
        return;
      }
      if (auto r = h.request.lock()) sendJson(r.get(), 200, w);
      return;
    case Ask::CheckBody:
      if (h.request.expired()) {  // its client left: a job nobody was told about does not start
        bridge->release();
        return;
      }
      if (h.spoolFailed) {
        bridge->release();
        writeError(w, "spool_failed", "the ESP could not store the job; its flash may be full");
        if (auto r = h.request.lock()) sendJson(r.get(), 503, w);
        return;
      }
      intake->begin();
      waiting = h.request;
      return;
    case Ask::None: return;
  }
}

}  // namespace

void beginPrintEndpoint(AsyncWebServer& server, Bridge& b, void (*serviceFn)()) {
  hubLock.begin();
  bridge = &b;
  service = serviceFn;
  static PrintIntake<FileBody, HeaderParse> theIntake(body, b, HeaderParse{});
  intake = &theIntake;
  server.on("/print", HTTP_POST, onPost, nullptr, onBody);
  server.on("/print", HTTP_DELETE, onDelete);
  server.on("/status", HTTP_GET, onStatus);
}

void pollPrintEndpoint() {
  for (Handed h; handed.take(h);) serve(h);
  if (!intake->busy()) return;
  if (waiting.expired()) {  // its client left: a job nobody was told about does not start
    intake->cancel();
    return;
  }
  if (intake->step(nextJobId) == Intake::Working) return;
  answer(waiting, intake->status(), intake->response());
  waiting.reset();
}

}  // namespace esp
}  // namespace uv
