// The WebSocket fan-out (protocol/esp.md "Back-pressure"): every message goes into one 8 KB ring,
// and each client reads it at its own pace. Putting a message in never waits for a client; a
// client that falls a whole ring behind is closed with 1008 ("too slow"). One ring for all
// clients keeps the memory fixed (8 KB) on the ESP8266, however many clients there are.
//
// Two sides, which may be two tasks (the ESP32's loop() and AsyncTCP's task), with no lock:
// - the writer (loop(): the bridge) puts messages in: broadcast, sendTo, count;
// - the readers' side (the network task, which alone touches the WebSocket library) lets clients
//   join and leave, and pumps the ring to them: join, leave, pump, lag.
// The writer overwrites what the slowest reader has not read; a reader copies a message out, then
// checks that the writer had not yet reserved its bytes again (a seqlock's check). A copy that may
// be torn is never sent: that reader was a ring behind, and is closed.
#pragma once
#include <stdint.h>

#include <atomic>

namespace uv {
namespace esp {

// The WebSocket server's side (ESPAsyncWebServer on the ESP). Called on the readers' side only.
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

  // --- the readers' side ---
  // A new connection reads from now on, beginning with the first message addressed to it (the
  // bridge's `hello`): what loop() broadcast before it heard of the client is skipped, so a client
  // is always greeted first (esp.md). False when kMaxClients are connected (close it: 1013).
  // `client` names it to the writer: a name is not given again while the writer may still
  // address its old holder (LiveSocket hands out fresh names).
  bool join(uint8_t client);
  void leave(uint8_t client);
  // Hands each client what it can take now, and closes those a ring behind.
  void pump();
  // Bytes of the ring a client has still to read.
  uint32_t lag(uint8_t client) const;

  // --- the writer's side ---
  // Queues a message for everyone, or for one client. False only for a message over kMaxMessage.
  bool broadcast(const char* text, uint16_t len) { return put(kEveryone, text, len); }
  bool sendTo(uint8_t client, const char* text, uint16_t len) { return put(client, text, len); }
  uint8_t count() const;
  // How much has been put in so far (bytes, wrapping): changed means there is news to send.
  uint32_t written() const { return head_.load(std::memory_order_relaxed); }
  // A client had a message waiting when its connection could take none (its queue not yet
  // empty) at the last pump: the readers' side needs another turn soon, news or not.
  bool backlogged() const { return backlog_.load(std::memory_order_relaxed); }

  // Either side.
  uint32_t closedSlow() const { return closedSlow_.load(std::memory_order_relaxed); }

 private:
  struct Reader {
    std::atomic<bool> used{false};
    uint8_t id = 0;
    uint32_t at = 0;  // absolute position in the message stream
    bool greeted = false;  // a message addressed to it was taken: broadcasts are its too from then on
  };
  static constexpr uint16_t kHeader = 4;  // length (2), addressee (1), spare (1)
  static constexpr uint16_t kWrap = 0xffff;

  bool put(uint8_t to, const char* text, uint16_t len);
  void store(uint16_t i, char c) { ring_[i].store(c, std::memory_order_relaxed); }
  uint8_t byteAt(uint32_t i) const { return static_cast<uint8_t>(ring_[i % kRing].load(std::memory_order_relaxed)); }
  // The entry at `at` (skipping wrap marks) before `head`; false at the end of what is written.
  bool entry(uint32_t& at, uint32_t head, uint16_t& len, uint8_t& to) const;
  void evict(Reader& r);

  LiveClients& clients_;
  std::atomic<char> ring_[kRing] = {};
  std::atomic<uint32_t> head_{0};     // where the next message goes (absolute); published after its bytes
  std::atomic<uint32_t> reserved_{0};  // the end of what the writer is writing: announced before its bytes
  Reader readers_[kMaxClients];
  char copy_[kMaxMessage];  // the readers' side's copy of the message being sent
  std::atomic<uint32_t> closedSlow_{0};
  std::atomic<bool> backlog_{false};
};

}  // namespace esp
}  // namespace uv
