// /ws: the library's events and sends on the network task, the bridge's side in loop().
#include "live_socket.h"

#include <ArduinoJson.h>

#include "board.h"
#include "http_rules.h"
#include "json_view.h"
#include "live_inbox.h"
#include "network.h"
#include "network_wake.h"

namespace uv {
namespace esp {

namespace {

LiveInbox inbox;  // network task in, loop() out
Bridge* bridge = nullptr;
LiveChannel* live = nullptr;

// --- the network task's ---
// The library's client ids (32-bit, never reused) by the name the live channel knows them by.
struct Named {
  uint8_t name;  // 0: a free place
  uint32_t id;
};
Named named[LiveChannel::kMaxClients] = {};
bool pumping = false;

Named* byName(uint8_t name) {
  for (Named& n : named)
    if (n.name && n.name == name) return &n;
  return nullptr;
}
Named* byId(uint32_t id) {
  for (Named& n : named)
    if (n.name && n.id == id) return &n;
  return nullptr;
}

// A whole message with no room in the inbox: the client is told at once, with its send's id.
void answerBusy(AsyncWebSocketClient* c) {
  JsonDocument doc;
  bool parsed = !deserializeJson(doc, inbox.busyText(), inbox.busyLength());
  JsonVariantConst id = doc["id"];
  bool hasId = parsed && id.is<int64_t>();
  char text[160];
  JsonWriter w(text, sizeof text);
  writeBusy(w, hasId, hasId ? id.as<int64_t>() : 0);
  if (w.ok()) c->text(w.text(), w.length());
}

void onEvent(AsyncWebSocket*, AsyncWebSocketClient* c, AwsEventType type, void* arg, uint8_t* data, size_t len) {
  if (type == WS_EVT_CONNECT) {
    Named* place = nullptr;
    for (Named& n : named)
      if (!n.name && !place) place = &n;
    uint8_t name = place ? inbox.join(kBoard.wsClients) : 0;
    if (!name || !live->join(name)) {
      if (name) inbox.leave(name);
      c->close(1013, "too many clients");
      return;
    }
    *place = Named{name, c->id()};
#if defined(ESP32)
    // The live channel is pumped from this connection's poll, on AsyncTCP's task, and at once when
    // loop() wakes the task (network_wake.h). It stands in for the library's own poll, which only
    // sends its queue (also sent at each ack and each text()) and pings when a keep-alive is set
    // (none is).
    c->client()->onPoll([](void*, AsyncClient*) { pumpNetwork(); }, nullptr);
#endif
  } else if (type == WS_EVT_DISCONNECT) {
    Named* n = byId(c->id());
    if (!n) return;
    live->leave(n->name);
    inbox.leave(n->name);
    *n = Named{0, 0};
  } else if (type == WS_EVT_DATA) {
    Named* n = byId(c->id());
    AwsFrameInfo* info = static_cast<AwsFrameInfo*>(arg);
    if (!n || info->message_opcode != WS_TEXT) return;
    // The message in pieces: its frames (num), and each frame in TCP segments (index).
    bool first = info->num == 0 && info->index == 0;
    bool last = info->final && info->index + len == info->len;
    if (inbox.received(n->name, reinterpret_cast<const char*>(data), len, first, last) == LiveInbox::Piece::Busy) answerBusy(c);
  }
  pumpNetwork();  // a join's greeting, a freed queue: whatever the channel holds for them
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
  inbox.drain(
      [](const LiveInbox::Member& m) {
        if (m.kind == LiveInbox::Kind::Joined) bridge->clientJoined(m.client, millis());
        else bridge->clientLeft(m.client);
      },
      [](const LiveInbox::Message& m) {
        if (m.kind == LiveInbox::Kind::TooLarge) return bridge->clientRefused(m.client, "too_large", "a message is at most 256 bytes");
        JsonDocument doc;
        if (deserializeJson(doc, m.text, m.len)) return bridge->clientRefused(m.client, "bad_json", "not JSON");
        bridge->clientMessage(m.client, JsonView{doc.as<JsonVariantConst>()});
      });
}

void LiveSocket::pump() {
  if (pumping) return;  // reached again from a send or a close that ran the library's callbacks
  pumping = true;
  live->pump();
  pumping = false;
}

// Only when the client's queue is empty: each client holds at most one heap copy of a message,
// and the ring keeps the rest (the library would keep up to WS_MAX_QUEUED_MESSAGES copies).
bool LiveSocket::trySend(uint8_t client, const char* text, uint16_t len) {
  Named* n = byName(client);
  if (!n) return true;  // gone: nothing to hold for it
  AsyncWebSocketClient* c = ws_.client(n->id);  // on the network task: not freed meanwhile
  if (!c) return true;
  if (c->queueLen() > 0) return false;
  return c->text(text, len);  // false only if it is closing: held, until its disconnect
}

void LiveSocket::close(uint8_t client, uint16_t code, const char* reason) {
  Named* n = byName(client);
  AsyncWebSocketClient* c = n ? ws_.client(n->id) : nullptr;
  if (c) c->close(code, reason);
}

}  // namespace esp
}  // namespace uv
