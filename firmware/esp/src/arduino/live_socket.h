// The WebSocket /ws on ESPAsyncWebServer (protocol/esp.md). Everything that touches the library
// (its events, sends, closes, client lookups) runs on the network task: on the ESP32 AsyncTCP's
// task, which frees clients itself; on the ESP8266 the SDK's callbacks and loop(), which never
// run at once. loop() reaches the clients only through the live channel's ring and the inbox's
// rings (live_channel.h, live_inbox.h), so no client is ever reached after it was freed.
#pragma once
#include <ESPAsyncWebServer.h>

#include "bridge.h"
#include "live_channel.h"

namespace uv {
namespace esp {

class LiveSocket : public LiveClients {
 public:
  explicit LiveSocket(AsyncWebSocket& ws) : ws_(ws) {}
  void begin(Bridge& bridge, LiveChannel& live);
  // loop(): hands the clients' joins, leaves and messages to the bridge.
  void drain();
  // The network task: the live channel's messages to the clients that can take one.
  void pump();

  // The live channel's, on the network task (from pump()).
  bool trySend(uint8_t client, const char* text, uint16_t len) override;
  void close(uint8_t client, uint16_t code, const char* reason) override;

 private:
  AsyncWebSocket& ws_;
};

}  // namespace esp
}  // namespace uv
