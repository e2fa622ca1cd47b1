// Codec for the Mega <-> Nano printhead link (protocol/nano.md): commands, replies, colours.
#pragma once
#include <stddef.h>
#include <stdint.h>

namespace uv {

constexpr uint8_t kNanoMaxLine = 63;
constexpr uint32_t kNanoBaud = 115200;  // 8N1: ten bits a byte; the power-on speed, and the one to fall back to
// The speeds an `L` may ask for (protocol/nano.md "Link speed"): 115200 and the three that are exact
// at 16 MHz with U2X (UBRR 7, 3 and 1). Any other is refused, never rounded to one of these.
// One byte's ten bits, in whole µs, at the divisor a 16 MHz AVR with U2X takes for `baud` (UBRR
// (F/4/baud − 1)/2, as Arduino rounds it): 85 at 115200 (117647 baud), 40 at 250000.
constexpr uint32_t linkByteUs(uint32_t baud) { return 5 * ((16000000 / 4 / baud - 1) / 2 + 1); }
inline bool nanoLinkBaud(uint32_t baud) { return baud == 115200 || baud == 250000 || baud == 500000 || baud == 1000000; }
constexpr uint8_t kLedCount = 4;
constexpr uint8_t kSensorCount = 6;

struct NanoCommand {
  char op;  // one of S F D U X P T R E V C G Q W L O (A and K lines: scan_program.h)
  uint8_t mask;
  uint32_t durations[kLedCount];
  uint32_t baud;  // L: the link speed asked for (nanoLinkBaud)
};

struct NanoReply {
  char op;  // one of S P T E V C K Q W L O
  uint8_t mask;
  bool triggered;
  int16_t deciC[kSensorCount];
  uint8_t flags;
  uint16_t protocol;
  char firmware[21];
  uint16_t boot;   // C: the Nano's start count
  uint32_t fires;  // C: exposures that lit since it started
  bool whole;      // C: the last exposure ran its full time (not cut by R or a fault)
  uint8_t code;    // K: the seal's SealCode
  uint8_t free, armed, pass;  // Q: buffers free to load, programs armed, the last chain's PassState
  uint32_t us;     // W: the Nano's micros() when the W's newline arrived
  uint32_t baud;   // L: the speed both sides take once this reply has gone out
  // O: a dose record (protocol/nano.md "Dose records"), or none waiting when `exposure` is 0.
  uint32_t exposure;           // the exposure's number, as C counts it (1 the first since start)
  uint16_t program;            // the program's place in its chain, 0 first; 0 for an F
  uint32_t onUs[kLedCount];    // how long each LED was lit, µs
};

enum class Colour : uint8_t { Green, DimWhite, Purple, Cyan, Orange, Red };

struct Rgb {
  uint8_t r, g, b;
};

// Fault bits of the E reply.
namespace fault {
constexpr uint8_t kOvertemp = 1, kSensor = 2, kCapped = 4, kBusy = 8, kRefused = 16,
                  kMalformed = 32, kWatchdog = 64, kCutoff = 128;
constexpr uint8_t kActive = kOvertemp | kSensor;
}  // namespace fault

Rgb colourRgb(Colour c);
Colour flashColour(char op);

// A line (without terminator) the Nano may parse: not overflowed, printable.
bool nanoLineUsable(const char* text, uint8_t len, bool overflow);

// Parses one command line. false = malformed (the Nano drops it).
bool parseNanoCommand(const char* line, uint8_t len, NanoCommand& out);
// Writes the command with its '\n' and a NUL; returns the length without the NUL.
size_t formatNanoCommand(const NanoCommand& cmd, char* out, size_t size);

// Writes one-decimal Celsius for tenths; returns the length.
size_t formatDeciC(int16_t deciC, char* out);

// The longest reply: "O:" and a 10-digit exposure, a 5-digit program and four 10-digit on-times,
// five commas (62 bytes), '\n' and a NUL.
constexpr size_t kNanoReplyMax = 64;
// Writes the reply in place; `size` must be at least kNanoReplyMax.
size_t formatNanoReply(const NanoReply& reply, char* out, size_t size);
// Parses a reply line including its '\n'. false = malformed.
bool parseNanoReply(const char* line, size_t len, NanoReply& out);

}  // namespace uv
