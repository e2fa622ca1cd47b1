// POST /print's body: spooled, checked in steps, answered, then uploaded; DELETE and GET /status.
#include "print_endpoint.h"

#include <ArduinoJson.h>
#include <LittleFS.h>

#include "file_body.h"
#include "http_rules.h"
#include "job_conversion.h"
#include "json_view.h"
#include "streamed_job_text.h"

namespace uv {
namespace esp {

namespace {

const char kSpool[] = "/job.json";  // the body: what the upload is made from again on a retry
const char kJobIdFile[] = "/jobid";

enum class Stage : uint8_t { Idle, Receiving, Checking, Converting };

struct NullSink : RecordSink {
  void record(const char*, uint8_t) override {}
};

Bridge* bridge = nullptr;
void (*service)() = nullptr;
Stage stage = Stage::Idle;
AsyncWebServerRequest* waiting = nullptr;  // the POST whose answer is being worked out
fs::File spool;
bool spoolFailed = false;
uint8_t cells[kJobMaxSide];  // one row: the check's, then the upload's
void serviceHook() {
  if (service) service();
}
FileBody body(LittleFS, kSpool, serviceHook);
NullSink nothing;
JobConversion<FileBody>* conversion = nullptr;
alignas(JobConversion<FileBody>) uint8_t conversionMem[sizeof(JobConversion<FileBody>)];
alignas(StreamedJobText<FileBody>) uint8_t textMem[sizeof(StreamedJobText<FileBody>)];
StreamedJobText<FileBody>* text = nullptr;
char reply[LiveChannel::kMaxMessage];

void sendJson(AsyncWebServerRequest* r, uint16_t status, const JsonWriter& w) { r->send(status, "application/json", w.text()); }

void sendError(AsyncWebServerRequest* r, uint16_t status, const char* code, const char* message, const char* path = "") {
  JsonWriter w(reply, sizeof reply);
  writeError(w, code, message, path);
  sendJson(r, status, w);
}

// Ends the POST being checked: its answer, and the spool goes unless the job was taken.
void finish(uint16_t status, const char* code, const char* message, const char* path) {
  if (waiting) sendError(waiting, status, code, message, path);
  waiting = nullptr;
  if (conversion) conversion->~JobConversion();
  conversion = nullptr;
  body.close();
  LittleFS.remove(kSpool);
  bridge->release();
  stage = Stage::Idle;
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
    stage = Stage::Receiving;
    waiting = r;
    r->onDisconnect([] {
      waiting = nullptr;  // nobody to answer; a body cut short is dropped below
    });
  }
  if (r != waiting || stage != Stage::Receiving) return;
  if (!spoolFailed && spool.write(data, len) != len) spoolFailed = true;
}

void onPost(AsyncWebServerRequest* r) {
  if (r->_tempObject) {
    const HttpError* e = static_cast<const HttpError*>(r->_tempObject);
    return sendError(r, e->status, e->code, e->message);
  }
  if (r != waiting || stage != Stage::Receiving) {  // no body at all
    HttpError e = admitPrintRequest(r->contentType().c_str(), true, 0, *bridge, millis());
    if (e.status) return sendError(r, e.status, e.code, e.message);
    bridge->release();
    return sendError(r, 400, "bad_json", "the body is empty");
  }
  spool.close();
  if (spoolFailed) return finish(503, "spool_failed", "the ESP could not store the job; its flash may be full", "");
  stage = Stage::Checking;  // loop() takes it from here
}

void onDelete(AsyncWebServerRequest* r) {
  JsonWriter w(reply, sizeof reply);
  w.beginObject().key("job").beginObject().key("state").string("aborted").endObject().endObject();
  if (stage != Stage::Idle) {
    finish(409, "cancelled", "cancelled by DELETE /print", "");
    return sendJson(r, 200, w);
  }
  if (!bridge->cancel()) return sendError(r, 409, "busy", "nothing to cancel");
  sendJson(r, 200, w);
}

void onStatus(AsyncWebServerRequest* r) {
  JsonWriter w(reply, sizeof reply);
  bridge->writeStatus(w, millis());
  sendJson(r, 200, w);
}

// The header: the whole body through ArduinoJson with gridData's contents skipped, which also
// checks its syntax. Then the rows, a few per loop pass.
void check() {
  if (!body.open()) return finish(503, "spool_failed", "the ESP could not read the job back", "");
  CappedAllocator cap(8192);
  JsonDocument doc(&cap);
  JsonDocument filter;
  filter["*"] = true;
  filter["gridData"] = false;
  DeserializationError err = deserializeJson(doc, body, DeserializationOption::Filter(filter));
  if (err == DeserializationError::NoMemory) return finish(400, "bad_job", "too many or too large fields", "");
  if (err) return finish(400, "bad_json", err.c_str(), "");
  if (!body.rewind()) return finish(503, "spool_failed", "the ESP could not read the job back", "");
  conversion = new (conversionMem) JobConversion<FileBody>(body, nothing, cells);
  if (!conversion->begin(JsonView{doc.as<JsonVariantConst>()})) {
    const RequestError& e = conversion->error();
    return finish(e.status, e.code, e.message, e.path);
  }
  stage = Stage::Converting;
}

void convert() {
  uint32_t start = millis();
  while (millis() - start < 20) {  // a share of each loop pass
    ConversionStep s = conversion->step();
    if (s == ConversionStep::More) continue;
    if (s == ConversionStep::Failed) {
      const RequestError& e = conversion->error();
      return finish(e.status, e.code, e.message, e.path);
    }
    // Accepted: answer, then upload the job text made again from the body as it is sent.
    JobHeader h = conversion->header();
    uint32_t bytes = conversion->textBytes();
    conversion->~JobConversion();
    conversion = nullptr;
    uint32_t id = nextJobId();
    if (text) text->~StreamedJobText();
    text = new (textMem) StreamedJobText<FileBody>(body, h, cells);
    if (waiting) {
      JsonWriter w(reply, sizeof reply);
      w.beginObject().key("job").beginObject().key("id").number(id).key("state").string("uploading");
      w.key("cells").number(static_cast<int64_t>(h.cols) * h.rows).endObject().endObject();
      sendJson(waiting, 202, w);
    }
    waiting = nullptr;
    stage = Stage::Idle;
    bridge->startUpload(id, *text, bytes);
    return;
  }
}

}  // namespace

void beginPrintEndpoint(AsyncWebServer& server, Bridge& b, void (*serviceFn)()) {
  bridge = &b;
  service = serviceFn;
  server.on("/print", HTTP_POST, onPost, nullptr, onBody);
  server.on("/print", HTTP_DELETE, onDelete);
  server.on("/status", HTTP_GET, onStatus);
}

void pollPrintEndpoint() {
  if (stage == Stage::Checking) check();
  else if (stage == Stage::Converting) convert();
}

}  // namespace esp
}  // namespace uv
