// The Mega's line-acceptance state machine: numbering, duplicates, resend and resync (protocol/mega.md §2).
#pragma once
#include <stddef.h>
#include <stdint.h>

#include "dialect_frame.h"

namespace uv {

// Where reply lines go (without '\n').
class ReplySink {
 public:
  virtual void line(const char* text) = 0;
};

class FlowCounters {
 public:
  virtual uint8_t movesFree() const = 0;
  virtual uint8_t windowFree() const = 0;
};

enum class Acceptance : uint8_t {
  None,     // empty line: no reply at all
  Replied,  // the receiver wrote the whole reply block
  Execute,  // run the frame's body; the command writes its reply, ending in ok()
};

class LineReceiver {
 public:
  explicit LineReceiver(const FlowCounters& flow) : flow_(flow) {}

  // Decides what a split line means. For Execute, `frame` holds the body to run.
  Acceptance accept(const char* text, uint8_t len, bool overflow, ReplySink& sink, Frame& frame);

  // The `ok` ending a reply block for line n (n < 0: a block that accepts no line), into out
  // (at least 48 bytes); returns the length. See protocol/mega.md §2.
  size_t formatOk(char* out, int32_t n = -1) const;
  void ok(ReplySink& sink, int32_t n = -1) const;

  int32_t last() const { return last_; }
  // The executor finished line n and is sending its reply block.
  void markAnswered(int32_t n) {
    if (n > answered_) answered_ = n;
  }
  bool resyncing() const { return resyncing_; }

 private:
  void askResend(uint8_t code, ReplySink& sink);
  bool m110(const Frame& f, int32_t& setTo) const;

  const FlowCounters& flow_;
  int32_t last_ = 0;      // -1 after `M110 N-1`
  int32_t answered_ = 0;  // the highest line whose reply block went out
  bool resyncing_ = false;
};

}  // namespace uv
