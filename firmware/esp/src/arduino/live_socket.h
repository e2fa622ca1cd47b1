// The WebSocket /ws on ESPAsyncWebServer (protocol/esp.md): its events arrive on the network
// task, so they are queued and handed to the bridge from loop(); messages go out through the
// live channel, which asks each connection whether it can take one now.
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
  // Hands queued client events to the bridge; call from loop().
  void drain();

  bool trySend(uint8_t client, const char* text, uint16_t len) override;
  void close(uint8_t client, uint16_t code, const char* reason) override;

 private:
  AsyncWebSocket& ws_;
};

}  // namespace esp
}  // namespace uv
