// The dialect's stable numeric error codes (protocol/errors.csv); never renumber.
#pragma once
#include <stdint.h>

namespace uv {

enum ErrorCode : uint8_t {
  kInvalidByte = 1,
  kChecksumMismatch = 2,
  kNoChecksum = 3,
  kNoLineNumber = 4,
  kLineTooLong = 5,
  kLineSequence = 6,
  kUnknownCommand = 10,
  kBadParameter = 11,
  kBusy = 12,
  kHalted = 13,
  kNotHomed = 14,
  kSoftLimit = 15,
  kNoSd = 20,
  kFileNotFound = 21,
  kFileError = 22,
  kJobMalformed = 23,
  kJobHashMismatch = 24,
  kJobIncomplete = 25,
  kNoJob = 26,
  kNoResume = 27,
  kStreamOverflow = 28,
  kScanUnsupported = 29,
  kNanoTimeout = 30,
  kOverTemperature = 31,
  kSensorFault = 32,
  kExposureRefused = 33,
  kLinkSpeed = 34,  // a scan job planned at a raised printhead link speed that the link no longer takes
  kProbeAlarm = 40,
  kProbeNoTrigger = 41,
  kEndstopHit = 42,
  kSelftestFailed = 43,
  kHomingFailed = 44,
  kConfigInvalid = 50,
};

// Codes 1-6 are line-level: a numbered line with one of them is asked for again.
inline bool isLineError(uint8_t code) { return code >= 1 && code <= 6; }

// The class column of errors.csv. Faults: the machine stopped or is in danger (`Error:`). Refusals leave it
// fine and are answered `echo:E<code> …`, as Marlin answers them, so hosts like OctoPrint stay connected.
inline bool isFault(uint8_t code) {
  return code == 13 || code == 28 || (code >= 30 && code <= 34) || (code >= 40 && code <= 44);
}
inline bool isRefusal(uint8_t code) { return !isLineError(code) && !isFault(code); }

// Copies the table's message for a code into out (NUL-terminated, truncated to size);
// for an unknown code it writes "unknown error" ("unknown" for the name) and returns false.
// Messages live in flash on AVR.
bool errorMessage(uint8_t code, char* out, uint8_t size);
// The table's name, e.g. "checksum_mismatch"; for tests and host tools.
bool errorName(uint8_t code, char* out, uint8_t size);

}  // namespace uv
