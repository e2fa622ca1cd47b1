// The Mega's dose report line (protocol/mega.md "Dose reports"): what the printhead delivered to one
// stop, or one program of a pass on the move, as the Nano's O record said. Canonical format (Mega
// side) and typed parse (host side).
#pragma once
#include <stddef.h>
#include <stdint.h>

namespace uv {

struct DoseReport {
  uint32_t stop;       // the job's stop, as JOB: counts them from 0 (a pass on the move is one)
  uint16_t program;    // the program's place in the pass's chain, 0 first; 0 for a stop
  uint32_t exposure;   // the Nano's exposure number (C counts them), 1 the first since it started
  uint32_t onUs[4];    // how long each LED was lit, in µs
  bool hasPlan;        // a stop: planUs holds what was sent (thermally compensated)
  uint32_t planUs[4];
  bool cut;            // the light was cut short (a fault, R, a restart): the stop is exposed again
  bool again;          // the stop had light before in this job: its cells got it twice
};

// Parses the payload after "DOSE:" in [p, end). false = malformed.
bool parseDoseReport(const char* p, const char* end, DoseReport& out);
// Writes "DOSE:..." and a NUL; returns its length, or 0 if it won't fit.
size_t formatDoseReport(const DoseReport& d, char* out, size_t size);
// The longest line: every number at its widest, plan, cut and again (without the NUL).
constexpr size_t kDoseReportMax = 10 + 10 + 6 + 5 + 5 + 10 + 4 + 43 + 6 + 43 + 6 + 8;  // 156

}  // namespace uv
