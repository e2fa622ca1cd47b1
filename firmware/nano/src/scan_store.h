// The printhead's two scan-program buffers (protocol/nano.md "Scan programs"): loading A and B lines,
// sealing with the check and the cap, and handing the running chain's events to the LED timer.
// Plain C++, tested on the host; the main loop loads and seals, the timer interrupt calls next().
#pragma once
#include <stdint.h>

#include "nano_codec.h"
#include "scan_program.h"

namespace nano {

class ScanStore {
 public:
  explicit ScanStore(uint32_t capUs) : capUs_(capUs) {}

  // Main loop. append() is false for a malformed line (the caller latches MALFORMED).
  // Not inlined into the main loop, where the AVR compiler ran short of registers and the seal's
  // loop spilled every value to the stack (1.4 ms for 64 events, measured in simavr).
  __attribute__((noinline)) bool append(const char* line, uint8_t len);
  __attribute__((noinline)) uv::SealCode seal(const uv::Seal& s);
  uint8_t freeBuffers() const;
  uint8_t armed() const;
  // The oldest armed program starts a chain, and nothing runs.
  bool startable() const;
  // With the timer idle: that program runs from its first event.
  void start();
  // Every program, loading, armed or running, is dropped; the pass becomes `why` if one ran.
  void discard(uv::PassState why);
  void refuse() { pass_ = uv::PassState::Refused; }
  uv::PassState pass() const { return pass_; }
  bool running() const { return run_ != kNone; }

  // For the dose records (dose_tally.h), main loop: a program the chain ran to its last event keeps
  // its buffer, spent, until the tally has read it; a spent buffer takes no load meanwhile.
  struct ProgramView {
    const uint32_t* words;  // as stored: pack(d, m)
    uint8_t count;
  };
  bool oldestSpent(ProgramView& v) const;
  void freeOldestSpent();
  // The running program, and how many of its events the timer has made (the one it waits for,
  // already taken, is not counted).
  bool runningProgram(ProgramView& v, uint8_t& made) const;

  // Timer interrupt: the running chain's next event, d in µs since the one before (or time 0).
  enum class Step : uint8_t { Event, End, Underrun };
  Step next(uint32_t& d, uint8_t& m) {
    uint32_t w;
    if (!take(w)) return nextProgram(d, m);
    d = delay(w);
    m = state(w);
    return Step::Event;
  }
  // The hot path of next(), for the timer between two close edges: the running program's next
  // event as stored (pack(d, m)), or false at the program's end, where next() takes over. A
  // cursor rather than an index: reaching buffer r's word i costs a 260-byte multiply. With the
  // store read inline the timer's step from one edge to the next fell from 20 µs to 9 µs
  // (nano_sim_tests, "Closer").
  bool take(uint32_t& w) {
    if (!left_) return false;
    left_--;
    w = *cur_++;
    return true;
  }
  // A stored word as Timer1 ticks (16 a µs) and as the LED state.
  static uint32_t ticks(uint32_t w) { return w & ~static_cast<uint32_t>(0x0F); }
  static uint8_t lights(uint32_t w) { return state(w); }

 private:
  static constexpr uint8_t kNone = 0xFF;
  enum State : uint8_t { Free, Loading, Armed, Running, Spent };
  // An event as stored: d above the LED state's 4 bits, so the timer gets d in ticks (16 a µs) and
  // the state by masking, with no shift between two edges (the main loop shifts when it loads).
  static uint32_t pack(uint32_t d, uint8_t m) { return d << 4 | m; }
  static uint32_t delay(uint32_t w) { return w >> 4; }
  static uint8_t state(uint32_t w) { return static_cast<uint8_t>(w) & 0x0F; }
  struct Buffer {
    uint32_t words[uv::kProgramEvents];  // pack(d, m)
    volatile uint8_t state;
    uint8_t count, flags, order;
  };
  void spoil(uv::SealCode why);
  __attribute__((noinline)) bool appendPacked(const char* line, uint8_t len);
  void openLoad();  // an A:0 or B:0: a free buffer for the new program (the unsealed one dropped)
  uint8_t oldestArmed() const { return oldestIn(Armed); }
  uint8_t oldestIn(uint8_t state) const;  // the program in `state` sealed first, or kNone
  // The chain's next program, or its end: next() once the running program's events are taken.
  __attribute__((noinline)) Step nextProgram(uint32_t& d, uint8_t& m);
  void runFrom(uint8_t i) {
    run_ = i;
    cur_ = buf_[i].words;
    left_ = buf_[i].count;
  }
  bool live(uint8_t i) const { return i != kNone && (buf_[i].state == Armed || buf_[i].state == Running); }

  uint32_t capUs_;
  Buffer buf_[2] = {};
  // Loading: which buffer, the next line number, the check so far, or why the load is spoiled.
  uint8_t loading_ = kNone;
  uint16_t nextSeq_ = 0;
  uint16_t check_ = uv::kCheckInit;
  uv::SealCode loadError_ = uv::SealCode::NoLoad;
  // The newest sealed program, which a continuation follows: its end state for the cap check.
  uint8_t newest_ = kNone;
  uint8_t chainMask_ = 0;
  uint32_t chainTail_[uv::kLedCount] = {};  // how long each lit LED has been on at its end, µs
  uint8_t order_ = 0;
  // Running.
  volatile uint8_t run_ = kNone;
  const uint32_t* cur_ = nullptr;  // the running program's next event, and how many are left
  uint8_t left_ = 0;
  volatile uv::PassState pass_ = uv::PassState::None;
};

}  // namespace nano
