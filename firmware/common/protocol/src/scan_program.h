// Scan programs on the printhead link (protocol/nano.md "Scan programs"): events, the A/B/K lines,
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
uint16_t checkWord(uint16_t crc, uint32_t w);  // the same from the word itself

// A B line's packing of one event word d × 16 + m (nano.md "B:q,<packed>"): 5 bits a character,
// most significant first, each character 63 + the bits, + 32 on every character but the word's last.
constexpr char kPackBase = '?';
constexpr uint8_t kPackMore = 32;
constexpr uint8_t kPackMaxChars = 7;
// Writes the word's characters into out (at least 7); returns how many (1-7).
uint8_t packWord(uint32_t w, char* out);

// Reads an `A:q,d,m[,d,m…]` or a `B:q,<packed>` line (without terminator) event by event, so
// nothing is held twice.
class AppendLine {
 public:
  // False when the line is not an A or B line with a number after it.
  bool begin(const char* line, uint8_t len);
  uint16_t seq() const { return seq_; }
  bool packed() const { return packed_; }
  // The next event; false at the end of the line or on a malformed event (then malformed()).
  bool next(uint32_t& d, uint8_t& m);
  // The same as the word d × 16 + m, for a B line only (what the Nano stores, unshifted).
  bool nextWord(uint32_t& w);
  bool malformed() const { return bad_; }

 private:
  const char* p_ = nullptr;
  const char* end_ = nullptr;
  uint16_t seq_ = 0;
  bool bad_ = false, packed_ = false;
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

// Cuts a pass's events into the chain's lines, one line per call, so a sender takes a line only
// when its UART has room for it (the Mega's ring holds one). Events come from `source` at absolute
// µs after time 0, in time order; each program holds at most 64 and each B line at most 63 bytes,
// and each program's K line follows its B lines (the packed A lines: A stays valid on the Nano).
class ProgramLines {
 public:
  // The next event; false at the end of the pass.
  using Source = bool (*)(void* ctx, uint32_t& t, uint8_t& m);
  ProgramLines(Source source, void* ctx) : source_(source), ctx_(ctx) {}
  // Writes the next line with its '\n' and a NUL into out[kNanoMaxLine + 2]; returns its length
  // without the NUL, or 0 once the chain is written. An event that goes backwards, repeats a time
  // or leaves a gap of 2²⁸ µs or more ends it early: failed() then says so, and the last program
  // was not sealed (the Nano never runs it).
  uint8_t next(char* out);
  bool failed() const { return failed_; }
  uint16_t programs() const { return programs_; }
  // The time of the last event written: after a K line, its program's last event.
  uint32_t lastUs() const { return last_; }

 private:
  bool peek();
  uint8_t seal(char* out);

  Source source_;
  void* ctx_;
  bool have_ = false;  // an event taken from the source, not yet placed
  uint32_t t_ = 0;
  uint8_t m_ = 0;
  bool ended_ = false, failed_ = false;
  bool any_ = false;   // an event was placed: last_ is its time
  uint32_t last_ = 0;
  uint16_t seq_ = 0;
  uint8_t events_ = 0;  // in the current program
  uint16_t check_ = kCheckInit;
  uint16_t programs_ = 0;
};

// Whether a pass's chain can cross the printhead link while it plays (planner.md "The printhead
// link"): fed the chain's lines in order, each with ProgramLines::lastUs() after it. The planner's
// link cap and the Mega's M29 both ask it, so a plan the planner makes is never refused.
class LinkLoad {
 public:
  // `baud`: the link's speed while the pass plays (one of nanoLinkBaud's).
  explicit LinkLoad(uint32_t baud) : baud_(baud) {}
  void add(const char* line, uint8_t n, uint32_t lastUs);
  // `passUs`: the pass's last event. False when the chain outruns the link: need > have, the first
  // rule broken (the whole chain's, else the first program that would come too late).
  bool fits(uint32_t passUs, uint64_t& need, uint64_t& have) const;
  // The bytes added, and those of the first two programs (all of them while fewer are sealed).
  uint32_t bytes() const { return bytes_; }
  uint32_t aheadBytes() const { return sealed_ >= 2 ? ahead_ : bytes_; }

 private:
  uint32_t baud_;
  uint32_t bytes_ = 0, ahead_ = 0, program_ = 0;  // all, the first two programs', the open program's
  uint32_t events_ = 0, aheadEvents_ = 0;         // all sealed, the first two programs'
  uint16_t sealed_ = 0;
  uint32_t end1_ = 0, end2_ = 0;  // the last event of the last program sealed and of the one before
  uint64_t need_ = 0, have_ = 0;  // the first program that would come too late
};

// The relay: what the Mega takes from the Nano freeing a buffer to the next program's first byte
// (it asks Q as the program before ends, mega/src/scan_run.h; the answer; a main-loop pass or two),
// and what a load loses besides: the gaps while the planner makes the next line, the K's 1.1 ms
// seal. The simavr scan tests measure relays up to 5.5 ms with both hosts polling the Mega, at the
// three Nano clocks (mega_sim_tests, "photo-like"); at 8000 that pass underran at ±0.5 %.
constexpr uint32_t kProgramRelayUs = 10000;

// What the Mega takes over an event as it writes a program's lines, and over the program's dose
// record. Making a line of some 20 events took 2 to 3 ms in simavr (a few, 4.5) once a duration and
// the Nano's clock took no 64-bit division (mega_sim_tests "photo-like", UV_MEGA_PROFILE; 4.7 to 6.1
// ms before), some 125 µs an event. What bounds it is the report: each program's O goes once it is
// armed, before the next Q (scan_run.cpp), and its answer takes milliseconds. At 175 µs the
// photo-like pass ran whole with every program reported at the three Nano clocks, the least slack
// 5.7 ms; at 150 a program came late and the Nano cut the chain.
constexpr uint32_t kProgramEventUs = 175;

// µs `bytes` take on the printhead link at `baud`, ten bits a byte.
inline uint64_t linkUs(uint32_t bytes, uint32_t baud) { return static_cast<uint64_t>(bytes) * 10 * 1000000 / baud; }
// µs lines of `bytes` holding `events` take to go out at `baud`: the wire's time, or the planner's if longer.
inline uint64_t sendUs(uint32_t bytes, uint32_t events, uint32_t baud) {
  const uint64_t wire = linkUs(bytes, baud), made = static_cast<uint64_t>(events) * kProgramEventUs;
  return wire > made ? wire : made;
}

}  // namespace uv
