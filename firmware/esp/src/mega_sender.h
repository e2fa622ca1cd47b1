// The ESP's side of protocol/mega.md: numbered lines with both checks, sent through the Mega's
// receive window, each answered line matched by its `ok N`, with resend and time-out recovery.
// Console lines from the WebSocket and an upload's records share it; each carries a tag, so its
// answer goes back to whoever sent it. Plain C++: the UART sits behind MegaWire.
#pragma once
#include <stdint.h>

#include "dialect_frame.h"
#include "dialect_reply.h"
#include "line_splitter.h"

namespace uv {
namespace esp {

// The UART to the Mega. write() takes all n bytes or none: the bridge never waits for the wire.
class MegaWire {
 public:
  virtual bool write(const char* data, uint16_t n) = 0;
};

constexpr uint16_t kRestartDropped = 0xffff;  // answered(): the line was dropped by a restart

class MegaListener {
 public:
  // Every line the Mega sends, as it arrives (the console's view).
  virtual void line(const char* text, uint8_t len) = 0;
  // The line queued with `tag` has been answered. `error` is the code of an Error: line in its
  // reply block (0 for none); line-level errors (1-6) never count, they belong to the link.
  // `ownBlock`: the lines since the previous ok were this line's reply block. It is false for a
  // line whose own ok was damaged on the wire, confirmed by a later ok.
  virtual void answered(uint16_t tag, uint16_t error, bool ownBlock) = 0;
  // A queued line goes on the wire for the first time.
  virtual void sent(const char* body, uint8_t len, uint16_t tag) {
    (void)body, (void)len, (void)tag;
  }
};

struct SenderHealth {
  uint32_t linesSent, resends, timeouts;
  uint32_t rttMs;  // smoothed first-send-to-acceptance time
};

class MegaSender {
 public:
  static constexpr uint8_t kQueue = 12;       // lines numbered and waiting or out
  static constexpr uint32_t kReplyTimeoutMs = 3000;  // over the Mega's 2 s busy: keep-alive

  MegaSender(MegaWire& wire, MegaListener& listener) : wire_(wire), listener_(listener), splitter_(rx_, sizeof rx_ - 1) {}

  // Queues one dialect line body (no N, no checksum). False when the queue is full or the line
  // would be too long: try again after an answer.
  bool send(const char* body, uint16_t tag);
  uint8_t free() const { return static_cast<uint8_t>(kQueue - count_); }
  bool idle() const { return count_ == 0; }
  // Bytes from the Mega.
  void received(char c, uint32_t nowMs);
  // Sends what the window allows and recovers from silence; call every loop pass.
  void poll(uint32_t nowMs);
  // After the Mega (re)started: its line counter is 0 again, so `M110 N0` goes first and the
  // queued lines are numbered anew. The newest queued line is dropped if the queue is full.
  void restart();
  // Takes back the lines with tags in [lo, hi] that were never sent (numbered lines must go, or the
  // Mega would wait for a missing number). Returns how many were taken back.
  uint8_t withdraw(uint16_t lo, uint16_t hi);

  uint8_t window() const { return window_; }
  // The newest job format (protocol/job.md) the Mega reads: 2 once its M115 said Cap:JOB_FORMAT:2,
  // else 1 (no answer yet, an older Mega, or one that restarted since).
  uint8_t jobFormat() const { return jobFormat_; }
  // The tag of the oldest line that has been on the wire, which the next ok answers (0xffff: none).
  uint16_t oldestSentTag() const;
  const SenderHealth& health() const { return health_; }

 private:
  struct Item {
    uint32_t n;
    uint16_t tag;
    bool numbered;
    bool sent;
    bool announced;  // listener told it went out (again after a restart)
    uint32_t firstMs;
    uint8_t len;
    char body[kDialectMaxLine];
  };
  Item& at(uint8_t i) { return items_[(head_ + i) % kQueue]; }
  void endBlock(const Reply& ok, uint32_t nowMs);
  void rewindTo(uint32_t n);
  uint32_t timeoutMs() const;

  MegaWire& wire_;
  MegaListener& listener_;
  char rx_[kDialectMaxLine + 40];
  LineSplitter splitter_;
  Item items_[kQueue];
  uint8_t head_ = 0, count_ = 0;
  uint8_t inflight_ = 0;
  uint8_t window_ = 1;          // until M115 says Cap:RX_WINDOW
  uint8_t jobFormat_ = 1;       // until M115 says Cap:JOB_FORMAT
  uint32_t next_ = 1;
  int64_t lastAccepted_ = 0;
  uint16_t blockError_ = 0;
  bool busySinceOk_ = false;
  uint32_t lastReplyMs_ = 0;
  uint32_t nowMs_ = 0;
  SenderHealth health_ = {};
};

}  // namespace esp
}  // namespace uv
