// POST /print, DELETE /print and GET /status on ESPAsyncWebServer (protocol/esp.md), split
// between the two tasks by the hand-over (hand_over.h), with nothing locked:
// - the network task (AsyncTCP's own FreeRTOS task on the ESP32; on the ESP8266 the SDK's
//   callbacks, which run only between loop()'s passes) owns every request: it judges a POST's
//   headers, stores its body on the spool, pauses the requests loop() must answer and hands them
//   over by ticket, and sends loop()'s answers from its own callbacks (NetworkDesk::pump);
// - loop() owns the bridge, the intake and the spool it was handed: it takes the work, checks a
//   body a step a pass and answers by ticket (LoopDesk).
// A request is only ever reached on the network task, through the AsyncWebServerRequestPtr that
// pause() gave, a weak pointer the library empties when the client goes.
#include "print_endpoint.h"

#include <ArduinoJson.h>
#include <LittleFS.h>

#include "file_body.h"
#include "flash_guard.h"
#include "http_rules.h"
#include "json_view.h"
#include "loop_desk.h"
#include "network.h"
#include "network_desk.h"
#include "network_wake.h"
#include "print_intake.h"

namespace uv {
namespace esp {

namespace {

const char kSpool[] = "/job.json";  // the body: the upload is made from it again on a retry
const char kJobIdFile[] = "/jobid";

void (*service)() = nullptr;
void serviceHook() {
  if (service) service();
}
FileBody body(LittleFS, kSpool, serviceHook, fileSystemGate);

// The header: the whole body through ArduinoJson with gridData's contents filtered out, which
// also checks the body's syntax, in at most 8 KB of heap. It runs in loop() and holds nothing the
// network task waits for: the spool is loop()'s until it says otherwise.
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

using BodyCheck = PrintIntake<FileBody, HeaderParse>;

HandOver rings;  // the only thing both tasks touch

// --- the network task's ---
NetworkDesk<AsyncWebServerRequestPtr> desk(rings);
AsyncWebServerRequest* receiving = nullptr;  // the POST whose body is arriving (identity only)
uint32_t receivingBody = 0;                   // its number (NetworkDesk::arriving)
uint32_t receivingSinceMs = 0;                // its body's first byte: the request's deadline counts from here
fs::File spool;
bool spoolFailed = false;
bool spoolFlashBusy = false;  // a part of the body came while loop() was inside a file operation
bool closeLater = false;      // the spool to close once loop() is out of the file system
char netReply[kErrorJsonBytes];  // answers the network task makes itself (off its small stack)

// --- loop()'s ---
LoopDesk<Bridge, BodyCheck>* loopDesk = nullptr;

// Network task.
void sendError(AsyncWebServerRequest* r, uint16_t status, const char* code, const char* message) {
  JsonWriter w(netReply, sizeof netReply);
  writeError(w, code, message);  // kErrorJsonBytes holds any error whole
  r->send(status, "application/json", w.text());
}

// Network task: the spool closed, now or (loop() inside a file operation) at the next callback.
// On the ESP8266 loop() reaches it too (pumpNetwork at the end of a pass), where the close may
// yield to the network callbacks: so the gate is held across it.
void closeSpool() {
  closeLater = flashBusy();
  if (closeLater) return;
  FlashGate::Hold hold(fileSystemGate);
  spool.close();
}

// Network task: loop()'s answers go out, each to its request if the client is still there.
void pump() {
  if (closeLater) closeSpool();
  desk.pump([](AsyncWebServerRequest& r, const Answer& a) { r.send(a.status, a.plainText ? "text/plain" : "application/json", a.body); });
}

// Network task: a paused request handed to loop(); with no room it is answered 503 at once.
void handOver(AsyncWebServerRequest* r, Ask ask, bool failed = false) {
  uint16_t ticket = desk.hand(r->pause(), ask, failed);
  if (!ticket) return sendError(r, 503, "overloaded", "too many requests are waiting for the ESP; try again");
  r->onDisconnect([ticket] { desk.left(ticket); });
  // Its connection's poll (on the network task on both chips; every 500 ms with AsyncTCP, and at
  // once when loop() wakes the task: network_wake.h) sends the answer once loop() has given it. It stands in for the request's own poll, which only pushes the rest of a
  // response too large for the connection's send buffer: ours (at most 2 KB) are written whole by
  // send(), and the rest of a larger one would still follow the client's acks.
  r->client()->onPoll([](void*, AsyncClient*) { pumpNetwork(); }, nullptr);
}

// loop(): the job's id, kept on flash across restarts.
uint32_t nextJobId() {
  FlashGate::Hold hold(fileSystemGate);
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

// Network task: the arriving body is let go of; nothing of it is kept, and the spool is free.
void dropArriving() {
  receiving = nullptr;
  closeSpool();
}

// Network task: a request answered by its _tempObject once whole (the library frees it with the request).
void answerLater(AsyncWebServerRequest* r, const HttpError& e) {
  if (!r->_tempObject) r->_tempObject = malloc(sizeof(HttpError));
  if (r->_tempObject) memcpy(r->_tempObject, &e, sizeof e);
}

// Network task: the POST's headers are judged before a byte of its body is kept, by what loop()
// last said of the Mega and the spool (loop() admits the Mega for real once the body is whole).
void onBody(AsyncWebServerRequest* r, uint8_t* data, size_t len, size_t index, size_t total) {
  if (index == 0) {
    pump();  // loop()'s latest notes first
    // A chunked body has no length to judge it by before it is read: 411.
    bool hasLength = !r->hasHeader("Transfer-Encoding");
    HttpError e = foreignRequest(r);
    if (!e.status) e = printHeaderError(r->contentType().c_str(), hasLength, static_cast<uint32_t>(total));
    if (!e.status && flashBusy()) e = HttpError{kFlashBusyStatus, kFlashBusyCode, kFlashBusyMessage};
    if (!e.status) e = admissionError(desk.admitBody());
    if (e.status) return answerLater(r, e);  // answered once the body has gone by; none of it is kept
    if (closeLater) closeSpool();  // not held: flashBusy() was false
    spool = LittleFS.open(kSpool, "w");
    spoolFailed = !spool;
    spoolFlashBusy = false;
    receiving = r;
    receivingBody = desk.arriving();
    receivingSinceMs = millis();
    r->onDisconnect([r] {
      // A client gone before its body was whole: what came is dropped, the spool is free again.
      if (r != receiving) return;
      dropArriving();
      desk.bodyAbandoned(receivingBody);
    });
    // A body that comes a byte every 2.9 s (under the library's 3 s idle time-out) is cut off at
    // its deadline (http_rules.h); the close runs the onDisconnect above. Before the body, the
    // library gives the glue nothing to time.
    r->client()->onPoll([r](void*, AsyncClient* c) {
      if (r == receiving && pastDeadline(receivingSinceMs, millis())) c->close();
    }, nullptr);
  }
  if (r != receiving) return;
  if (flashBusy()) spoolFlashBusy = true;  // not written now, so the body cannot be whole: 503 flash_busy
  if (!spoolFailed && !spoolFlashBusy && spool.write(data, len) != len) spoolFailed = true;
}

// Network task: the whole request is in.
void onPost(AsyncWebServerRequest* r) {
  pump();
  if (r->_tempObject) {
    const HttpError* e = static_cast<const HttpError*>(r->_tempObject);
    if (strcmp(e->code, kFlashBusyCode) == 0) return sendFlashBusy(r);  // with its Retry-After
    return sendError(r, e->status, e->code, e->message);
  }
  if (r != receiving) {  // no body at all: what the headers say, or 400
    HttpError e = foreignRequest(r);
    if (!e.status) e = printHeaderError(r->contentType().c_str(), true, 0);
    if (!e.status) e = admissionError(desk.admission());
    if (e.status) return sendError(r, e.status, e.code, e.message);
    return sendError(r, 400, "bad_json", "the body is empty");
  }
  dropArriving();
  if (spoolFlashBusy || closeLater) {  // a part of it was not kept, or the spool is not yet closed
    desk.bodyAbandoned(receivingBody);
    return sendFlashBusy(r);
  }
  handOver(r, Ask::CheckBody, spoolFailed);  // the spool goes with it; loop() checks it and answers
}

void onDelete(AsyncWebServerRequest* r) {
  pump();
  HttpError e = foreignRequest(r);
  if (e.status) return sendError(r, e.status, e.code, e.message);
  if (desk.cancelArriving()) {  // the body arriving: the spool is free at once, its POST told once whole
    answerLater(receiving, HttpError{409, kCancelledCode, kCancelledMessage});
    dropArriving();
    return r->send(200, "application/json", kCancelledJson);
  }
  handOver(r, Ask::Cancel);
}

void onStatus(AsyncWebServerRequest* r) {
  pump();
  handOver(r, Ask::Status);
}

}  // namespace

void beginPrintEndpoint(AsyncWebServer& server, Bridge& bridge, void (*serviceFn)()) {
  service = serviceFn;
  static BodyCheck check(body, bridge, HeaderParse{});
  static LoopDesk<Bridge, BodyCheck> theDesk(rings, bridge, check);
  loopDesk = &theDesk;
  server.on("/print", HTTP_POST, onPost, nullptr, onBody);
  server.on("/print", HTTP_DELETE, onDelete);
  server.on("/status", HTTP_GET, onStatus);
}

void pollPrintEndpoint() {
  loopDesk->poll(millis(), nextJobId);
  if (rings.answers.room() < 2) wakeNetwork();  // an answer waits for the network task
}

void pumpPrintEndpoint() { pump(); }

}  // namespace esp
}  // namespace uv
