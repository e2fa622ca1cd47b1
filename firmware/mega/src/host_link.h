// One host-facing port (USB or the ESP's UART), protocol/mega.md §1-3: the receive interrupt fills
// the line ring, the main loop accepts lines and runs them in order, and replies go out through a
// transmit ring that the transmit interrupt empties, so no reply ever waits for the wire.
#pragma once
#include <stdint.h>

#include "dialect_receiver.h"
#include "line_ring.h"

namespace mega {

// One reply block (the longest payload line, 112 bytes, and its ok) fits whole; 143 usable.
constexpr uint8_t kTxRing = 144;
constexpr uint8_t kAcceptRoom = 96;   // free bytes the receiver needs to answer a line at once (errors, resend)

// Starts the transmit interrupt when bytes are waiting (hw/host_uart on the board).
class TxPort {
 public:
  virtual void kick() = 0;
};

class HostLink final : public uv::ReplySink, private uv::FlowCounters {
 public:
  // movesFree: the motion queue's free slots, for the P field of every ok. window: this port's
  // line slots (kUsbWindow, kEspWindow).
  HostLink(TxPort& tx, const uint8_t& movesFree, LineWindow window) : tx_(tx), moves_(movesFree), receiver_(*this), ring_(window) {}

  // --- interrupts ---
  void received(char c) { ring_.received(c); }
  // The next byte to send, or -1 when the ring is empty.
  int16_t nextTx() {
    if (txIn_ == txOut_) return -1;
    char c = txBuf_[txOut_];
    txOut_ = txOut_ + 1 == kTxRing ? 0 : static_cast<uint8_t>(txOut_ + 1);
    return static_cast<uint8_t>(c);
  }

  // --- main loop ---
  // Accepts the lines that have arrived. Returns true if one was M112: the caller acts on it at
  // once, ahead of every queued line (protocol/mega.md §5).
  bool poll();
  // The oldest accepted line not yet answered, or nullptr.
  const LineSlot* front() { return ring_.front(); }
  uint8_t queued() const { return ring_.queued(); }
  // Lines the host may have unanswered on this port (Cap:RX_WINDOW).
  uint8_t window() const { return ring_.window(); }
  // Ends the front line's reply block with its ok and frees its slot.
  void ok();
  void error(uint8_t code, const char* detail = nullptr) {
    errorLine(code, detail);
    ok();
  }
  // Just the `Error:E<code> <message>[: detail]` line (`echo:E…` for a refusal, mega.md §2); errorLineP takes a detail in flash (UV_P).
  void errorLine(uint8_t code, const char* detail = nullptr) { errorLine(code, detail, false); }
  void errorLineP(uint8_t code, const char* detail) { errorLine(code, detail, true); }
  // The code of the last error line, for the core to see a G-code file's line fail (0: none since reset).
  uint8_t lastError = 0;

  // Queues one line and '\n' if it fits whole; false (nothing queued) if not.
  bool report(const char* text) { return write(text, false); }
  // The same for a line in flash (UV_P).
  bool reportP(const char* text) { return write(text, true); }
  void lineP(const char* text) { line(text, true); }
  // Free transmit bytes.
  uint8_t room() const { return txFree(); }
  bool takeHeard() {
    bool h = heard_;
    heard_ = false;
    return h;
  }
  uint16_t dropped() const { return ring_.dropped(); }
  // Lines that found no room and were not sent: none, when every caller makes room first.
  uint16_t txDropped() const { return txDropped_; }

  void line(const char* text) override { line(text, false); }  // queued whole, or not at all

 private:
  uint8_t movesFree() const override { return moves_; }
  uint8_t windowFree() const override { return ring_.free(); }
  uint8_t txFree() const {
    uint8_t in = txIn_, out = txOut_;
    return static_cast<uint8_t>(kTxRing - 1 - (in >= out ? in - out : kTxRing - out + in));
  }
  void put(const char* text, uint8_t n, bool flash = false);
  bool write(const char* text, bool flash);
  void line(const char* text, bool flash);
  void errorLine(uint8_t code, const char* detail, bool flash);

  TxPort& tx_;
  const uint8_t& moves_;
  uv::LineReceiver receiver_;
  LineRing ring_;
  char txBuf_[kTxRing];
  volatile uint8_t txIn_ = 0, txOut_ = 0;
  bool heard_ = false;
  uint16_t txDropped_ = 0;
};

// True if a line's body is M112, whatever its frame: it is obeyed before it is even checked.
bool isEmergencyStop(const char* line, uint8_t len);

}  // namespace mega
