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

  uint32_t last() const { return last_; }
  bool resyncing() const { return resyncing_; }

 private:
  void askResend(uint8_t code, ReplySink& sink);
  bool m110(const Frame& f, uint32_t& setTo) const;

  const FlowCounters& flow_;
  uint32_t last_ = 0;
  bool resyncing_ = false;
};

}  // namespace uv
