// /ws: client events queued from the network task, handed to the bridge in loop().
#include "live_socket.h"

#include <ArduinoJson.h>

#include "http_rules.h"
#include "json_view.h"
#include "network.h"

#if defined(ESP32)
#include <freertos/FreeRTOS.h>
static portMUX_TYPE inboxLock = portMUX_INITIALIZER_UNLOCKED;
#define INBOX_LOCK() portENTER_CRITICAL(&inboxLock)
#define INBOX_UNLOCK() portEXIT_CRITICAL(&inboxLock)
#else  // ESP8266: network callbacks never preempt loop()
#define INBOX_LOCK()
#define INBOX_UNLOCK()
#endif

namespace uv {
namespace esp {

namespace {

constexpr uint16_t kMaxFrame = 256;  // a `send` is under 150 bytes of JSON
constexpr uint8_t kInbox = 8;

enum class Kind : uint8_t { Joined, Left, Text, TooLarge };
struct Event {
  Kind kind;
  uint8_t client;
  uint16_t len;
  char text[kMaxFrame + 1];
};

Event inbox[kInbox];
uint8_t inHead = 0, inCount = 0;
uint32_t inboxDropped = 0;
Bridge* bridge = nullptr;
LiveChannel* live = nullptr;
// The live channel names clients by a byte; the library's ids are 32-bit and never reused.
uint32_t ids[LiveChannel::kMaxClients + 1];

void push(Kind kind, uint8_t client, const uint8_t* data, size_t len) {
  INBOX_LOCK();
  if (inCount < kInbox) {
    Event& e = inbox[(inHead + inCount) % kInbox];
    e.kind = kind;
    e.client = client;
    e.len = static_cast<uint16_t>(len);
    if (data) memcpy(e.text, data, len);
    e.text[len] = 0;
    inCount++;
  } else {
    inboxDropped++;
  }
  INBOX_UNLOCK();
}

int8_t slotOf(uint32_t id) {
  for (uint8_t i = 1; i <= LiveChannel::kMaxClients; i++)
    if (ids[i] == id) return static_cast<int8_t>(i);
  return -1;
}

void onEvent(AsyncWebSocket*, AsyncWebSocketClient* c, AwsEventType type, void* arg, uint8_t* data, size_t len) {
  if (type == WS_EVT_CONNECT) {
    int8_t slot = slotOf(0);
    if (slot < 0) {
      c->close(1013, "too many clients");
      return;
    }
    ids[slot] = c->id();
    push(Kind::Joined, static_cast<uint8_t>(slot), nullptr, 0);
  } else if (type == WS_EVT_DISCONNECT) {
    int8_t slot = slotOf(c->id());
    if (slot < 0) return;
    ids[slot] = 0;
    push(Kind::Left, static_cast<uint8_t>(slot), nullptr, 0);
  } else if (type == WS_EVT_DATA) {
    int8_t slot = slotOf(c->id());
    AwsFrameInfo* info = static_cast<AwsFrameInfo*>(arg);
    if (slot < 0 || info->opcode != WS_TEXT) return;
    // Only whole frames; a message in pieces or over kMaxFrame is refused, not reassembled.
    if (!info->final || info->index != 0 || info->len != len || len > kMaxFrame) {
      if (info->index == 0) push(Kind::TooLarge, static_cast<uint8_t>(slot), nullptr, 0);
      return;
    }
    push(Kind::Text, static_cast<uint8_t>(slot), data, len);
  }
}

}  // namespace

void LiveSocket::begin(Bridge& b, LiveChannel& l) {
  bridge = &b;
  live = &l;
  ws_.onEvent(onEvent);
  // /ws drives the Mega and has no CORS preflight: a handshake from a foreign page is refused
  // before the upgrade (protocol/esp.md "Who may drive it"). A handler's middleware runs before
  // its handleRequest, which answers 101.
  ws_.addMiddleware([](AsyncWebServerRequest* r, ArMiddlewareNext next) {
    HttpError e = foreignRequest(r);
    if (!e.status) return next();
    static char refusal[kErrorJsonBytes];  // network task only; off its small stack
    JsonWriter w(refusal, sizeof refusal);
    writeError(w, e.code, e.message);
    r->send(e.status, "application/json", w.text());
  });
}

void LiveSocket::drain() {
  for (;;) {
    Event e;
    INBOX_LOCK();
    bool any = inCount > 0;
    if (any) {
      e = inbox[inHead];
      inHead = static_cast<uint8_t>((inHead + 1) % kInbox);
      inCount--;
    }
    INBOX_UNLOCK();
    if (!any) return;
    switch (e.kind) {
      case Kind::Joined:
        if (live->join(e.client)) bridge->clientJoined(e.client, millis());
        break;
      case Kind::Left:
        live->leave(e.client);
        bridge->clientLeft(e.client);
        break;
      case Kind::TooLarge: bridge->clientRefused(e.client, "too_large", "a message is at most 256 bytes, in one frame"); break;
      case Kind::Text: {
        JsonDocument doc;
        if (deserializeJson(doc, e.text, e.len)) {
          bridge->clientRefused(e.client, "bad_json", "not JSON");
          break;
        }
        bridge->clientMessage(e.client, JsonView{doc.as<JsonVariantConst>()});
        break;
      }
    }
  }
}

bool LiveSocket::trySend(uint8_t client, const char* text, uint16_t len) {
  if (client > LiveChannel::kMaxClients || !ids[client]) return true;  // gone: nothing to hold for it
  AsyncWebSocketClient* c = ws_.client(ids[client]);
  if (!c) return true;
  if (!c->canSend()) return false;  // its queue is full: the live channel keeps the message
  c->text(text, len);
  return true;
}

void LiveSocket::close(uint8_t client, uint16_t code, const char* reason) {
  if (client > LiveChannel::kMaxClients || !ids[client]) return;
  AsyncWebSocketClient* c = ws_.client(ids[client]);
  if (c) c->close(code, reason);
}

}  // namespace esp
}  // namespace uv
