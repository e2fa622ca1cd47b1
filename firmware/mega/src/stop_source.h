// Where a running job's stops come from: the stop file of a job planned on the card, or the
// planner itself while a stream's rows arrive (stream_job.h).
#pragma once
#include <stdint.h>

#include "time_model.h"

namespace mega {

enum class NextStop : uint8_t { Stop, Wait, End, Error };

class StopSource {
 public:
  // Stop `index` (asked in order, from the first). Wait: not planned yet (a stream waits for rows).
  virtual NextStop next(uint32_t index, uv::Stop& out) = 0;
  // Stops known so far; all of them once complete().
  virtual uint32_t count() const = 0;
  virtual bool complete() const = 0;
};

}  // namespace mega
