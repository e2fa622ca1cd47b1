// Where a running job's stops come from: the stop file of a job planned on the card, or the
// planner itself while a stream's rows arrive (stream_job.h).
#pragma once
#include <stdint.h>

#include "scan_run.h"
#include "time_model.h"

namespace mega {

// Scan: the job is exposed on the move, pass by pass (scanStep), not stop by stop.
enum class NextStop : uint8_t { Stop, Wait, End, Error, Scan };

class StopSource {
 public:
  // Stop `index` (asked in order, from the first). Wait: not planned yet (a stream waits for rows).
  virtual NextStop next(uint32_t index, uv::Stop& out) = 0;
  // Stops known so far; all of them once complete().
  virtual uint32_t count() const = 0;
  virtual bool complete() const = 0;
  // A scan job's passes (after next() said Scan): the next step of the one under way, and why the
  // last failed. Passes count as its stops in count().
  virtual ScanRun::Step scanStep(Motion& motion, PrintheadLink& head, uint32_t nowUs) {
    (void)motion, (void)head, (void)nowUs;
    return ScanRun::Step::End;
  }
  virtual uint8_t scanError() const { return 0; }
};

}  // namespace mega
