// The WebSocket fan-out (protocol/esp.md "Back-pressure"): every message goes into one 8 KB ring,
// and each client reads it at its own pace. Putting a message in never waits for a client; a
// client that falls a whole ring behind is closed with 1008 ("too slow"). One ring for all
// clients keeps the memory fixed (8 KB) on the ESP8266, however many clients there are.
#pragma once
#include <stdint.h>

namespace uv {
namespace esp {

// The WebSocket server's side (ESPAsyncWebServer on the ESP).
class LiveClients {
 public:
  // Hands one text frame to the client's connection; false if it can't take one now.
  virtual bool trySend(uint8_t client, const char* text, uint16_t len) = 0;
  virtual void close(uint8_t client, uint16_t code, const char* reason) = 0;
};

class LiveChannel {
 public:
  static constexpr uint16_t kRing = 8192;
  static constexpr uint8_t kMaxClients = 4;
  static constexpr uint8_t kEveryone = 0xff;
  static constexpr uint16_t kMaxMessage = 2048;

  explicit LiveChannel(LiveClients& clients) : clients_(clients) {}

  // A new connection reads from now on. False when kMaxClients are connected (close it: 1013).
  bool join(uint8_t client);
  void leave(uint8_t client);
  uint8_t count() const;

  // Queues a message for everyone, or for one client. False only for a message over kMaxMessage.
  bool broadcast(const char* text, uint16_t len) { return put(kEveryone, text, len); }
  bool sendTo(uint8_t client, const char* text, uint16_t len) { return put(client, text, len); }

  // Hands each client what it can take now; call every loop pass.
  void pump();

  uint32_t closedSlow() const { return closedSlow_; }
  // Bytes of the ring a client has still to read.
  uint32_t lag(uint8_t client) const;

 private:
  struct Reader {
    bool used;
    uint8_t id;
    uint32_t at;  // absolute position in the message stream
  };
  static constexpr uint16_t kHeader = 4;  // length (2), addressee (1), spare (1)
  static constexpr uint16_t kWrap = 0xffff;

  bool put(uint8_t to, const char* text, uint16_t len);
  void makeRoom(uint32_t upTo);
  // The entry at `at`; false at the end of what is written.
  bool entry(uint32_t& at, uint16_t& len, uint8_t& to, const char*& text) const;

  LiveClients& clients_;
  char ring_[kRing];
  uint32_t head_ = 0;  // where the next message goes (absolute)
  Reader readers_[kMaxClients] = {};
  uint32_t closedSlow_ = 0;
};

}  // namespace esp
}  // namespace uv
