// Replies and reports of the Mega dialect: canonical format (Mega side) and typed parse (ESP side).
#pragma once
#include <stddef.h>
#include <stdint.h>

#include "dialect_dose.h"
#include "nano_codec.h"

namespace uv {

enum class ReplyKind : uint8_t {
  Ok, Error, Resend, Temps, Position, Job, Probe, ProbePoint, Test, Fault, Echo, Busy, Start,
  Firmware, Cap, Other, Dose,
};

// Index order matches the names in dialect_reply.cpp and protocol/mega.md §4.
enum class JobState : uint8_t { Idle, Uploading, Ready, Running, Paused, Done, Aborted, Failed, Interrupted };
enum class ProbeState : uint8_t { Triggered, Open, Alarm, Deployed, Stowed };

extern const char kMachineType[];  // in flash on AVR

struct Reply {
  ReplyKind kind;
  bool hasFlow;          // ok: P/B (and N, if hasN) came with an intact checksum
  bool hasN;             // ok: it answers line n
  uint32_t n;            // ok N, resend n
  uint16_t p, b;         // ok P, B
  uint16_t code;         // error / fault code; 0 = an error without a code
  uint32_t value;        // cap value, firmware protocol version
  uint8_t state;         // JobState, ProbeState, or test mode (0 quick, 1 full)
  int16_t deciC[kSensorCount];
  int32_t um[3];
  int32_t steps[3];
  const char* text;      // into the line: message, echo text, ` k=v` fields, firmware name, cap name, other
  uint8_t textLen;
  DoseReport dose;       // DOSE:
};

// Parses one line from the Mega. false = a known prefix with a malformed payload.
bool parseReply(const char* line, uint8_t len, Reply& out);

// Writes the canonical line for a reply and a NUL; returns its length (0 if it won't fit).
size_t formatReply(const Reply& r, char* out, size_t size);

// The state's name (a flash pointer on AVR).
const char* jobStateName(JobState s);

}  // namespace uv
