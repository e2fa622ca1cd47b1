// Scan programs on the printhead link (protocol/nano.md "Scan programs"): events, the A/K lines,
// the check, and the writer that cuts a pass's events into a chain of programs.
#pragma once
#include <stddef.h>
#include <stdint.h>

#include "nano_codec.h"

namespace uv {

constexpr uint8_t kProgramEvents = 64;                 // events a program holds
constexpr uint32_t kProgramMaxDelta = (1UL << 28) - 1;  // d of one event, µs
constexpr uint32_t kProgramStartLeadUs = 1000;         // time 0 after the '\n' of G arrives
constexpr uint32_t kProgramLateUs = 800;               // a G taken later than this is refused
constexpr uint32_t kChainSilenceMs = 50;               // a running chain with no line for longer is cut
constexpr uint8_t kSealContinuation = 1, kSealMore = 2;
constexpr uint16_t kCheckInit = 0xFFFF;

// The K reply's code.
enum class SealCode : uint8_t { Armed, NoLoad, Mismatch, Capped, EndsLit, TooMany, NoBuffer, BadStart };
// The Q reply's pass state.
enum class PassState : uint8_t { None, Running, Whole, CutByReset, CutByFault, Underrun, Refused, CutBySilence };

// The check of a program: CRC-16/CCITT-FALSE over each event's word d × 16 + m, 4 bytes LE.
uint16_t checkEvent(uint16_t crc, uint32_t d, uint8_t m);

// Reads an `A:q,d,m[,d,m…]` line (without terminator) pair by pair, so nothing is held twice.
class AppendLine {
 public:
  // False when the line is not an A line with a number after it.
  bool begin(const char* line, uint8_t len);
  uint16_t seq() const { return seq_; }
  // The next pair; false at the end of the line or on a malformed pair (then malformed()).
  bool next(uint32_t& d, uint8_t& m);
  bool malformed() const { return bad_; }

 private:
  const char* p_ = nullptr;
  const char* end_ = nullptr;
  uint16_t seq_ = 0;
  bool bad_ = false;
};

struct Seal {
  uint8_t flags;
  uint8_t events;
  uint16_t check;
};
// Parses `K:f,n,c`; false = malformed (f over 3, n not 1-64, c over 65535).
bool parseSeal(const char* line, uint8_t len, Seal& out);
// Writes `K:f,n,c\n` and a NUL into out (at least 24 bytes); returns the length without the NUL.
size_t formatSeal(const Seal& s, char* out);

// Cuts a pass's events, given at absolute µs after time 0 in time order, into programs of at most
// 64 events and those into A lines of at most 63 bytes. Feed events with add(), then finish();
// each completed line goes to the sink, and each completed program's K line after its A lines.
class ProgramWriter {
 public:
  using Sink = void (*)(void* ctx, const char* line, size_t len);
  ProgramWriter(Sink sink, void* ctx) : sink_(sink), ctx_(ctx) {}
  // false (and nothing sent) when t goes backwards, repeats, or leaves a gap of 2²⁸ µs or more.
  bool add(uint32_t t, uint8_t m);
  // Seals the last program (the end of the chain); false when nothing was added.
  bool finish();
  uint16_t programs() const { return programs_; }

 private:
  void flushLine();
  void seal(bool more);

  Sink sink_;
  void* ctx_;
  char line_[kNanoMaxLine + 2];  // a full line, its newline and a NUL
  uint8_t len_ = 0;
  uint16_t seq_ = 0;
  uint8_t events_ = 0;  // in the current program
  uint16_t check_ = kCheckInit;
  uint32_t last_ = 0;
  bool any_ = false;
  uint16_t programs_ = 0;
};

}  // namespace uv
