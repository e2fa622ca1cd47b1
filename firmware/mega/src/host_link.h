// One host-facing port (USB or the ESP's UART): bytes to accepted lines (protocol/mega.md §1-3),
// a queue of accepted lines as deep as the receive window, and a transmit ring that drains into the
// UART as it takes bytes, so no reply ever waits for the wire.
#pragma once
#include <stdint.h>

#include "byte_stream.h"
#include "dialect_receiver.h"
#include "line_splitter.h"

namespace mega {

constexpr uint8_t kWindow = 8;          // Cap:RX_WINDOW
constexpr uint16_t kTxRing = 256;
constexpr uint16_t kTxReserve = 128;    // kept free for the receiver's own replies

struct QueuedLine {
  int32_t n;       // the line's number, -1 for a plain line
  uint8_t len;
  char body[uv::kDialectMaxLine + 1];  // NUL-terminated
};

class HostLink : public uv::ReplySink, private uv::FlowCounters {
 public:
  // movesFree: the motion queue's free slots, for the P field of every ok.
  HostLink(ByteStream& io, const uint8_t& movesFree) : io_(io), moves_(movesFree), receiver_(*this), splitter_(line_, uv::kDialectMaxLine) {}

  // Reads what has arrived and sends what is waiting. Returns true if an M112 arrived: the caller
  // acts on it at once, ahead of every queued line (protocol/mega.md §5).
  bool poll();

  // The oldest accepted line not yet answered, or nullptr.
  const QueuedLine* front() const { return count_ ? &queue_[head_] : nullptr; }
  uint8_t queued() const { return count_; }
  // Ends the front line's reply block with its ok and frees its slot.
  void ok();
  // An error line for the front line, then its ok.
  void error(uint8_t code, const char* detail = nullptr) {
    errorLine(code, detail);
    ok();
  }
  // Just the `Error:E<code> <message>[: detail]` line.
  void errorLine(uint8_t code, const char* detail = nullptr);

  // Queues one line and '\n'. False (nothing queued) if the ring lacks room above the reserve.
  bool report(const char* text);
  // Free bytes in the transmit ring above the reserve.
  uint16_t room() const;
  // Every byte handed to the UART.
  bool drained() const { return txCount_ == 0; }
  // Any line arrived since the last call (a host is there).
  bool takeHeard() {
    bool h = heard_;
    heard_ = false;
    return h;
  }

  void line(const char* text) override;  // for the receiver and replies: uses the reserve

 private:
  uint8_t movesFree() const override { return moves_; }
  uint8_t windowFree() const override { return static_cast<uint8_t>(kWindow - count_); }
  void put(const char* text, uint16_t n);
  void pump();

  ByteStream& io_;
  const uint8_t& moves_;
  uv::LineReceiver receiver_;
  char line_[uv::kDialectMaxLine + 1];
  uv::LineSplitter splitter_;
  bool lineWaiting_ = false;  // a split line waits for transmit room to be accepted
  QueuedLine queue_[kWindow];
  uint8_t head_ = 0, count_ = 0;
  char tx_[kTxRing];
  uint16_t txHead_ = 0, txCount_ = 0;
  bool heard_ = false;
};

// True if a line's body is M112, whatever its frame: it is obeyed before it is even checked.
bool isEmergencyStop(const char* line, uint8_t len);

}  // namespace mega
