// The exposure planner (protocol/planner.md): streams a job's stops one at a time from a CellSource.
#pragma once
#include <stdint.h>

#include "cell_source.h"
#include "job_types.h"

namespace uv {

constexpr uint16_t kPlannerMaxRows = kJobMaxSide;
constexpr uint8_t kRandomBlock = 32;
// The bound the host tests hold the planner to: its whole state, at any grid size.
constexpr uint16_t kPlannerMaxBytes = 900;

struct Stop {
  int32_t hx, hy;   // head position in cells
  uint32_t us[4];   // per LED
};

// t_k(v) for one LED: round(full_k × gain_k × m(v) / 255000).
class Durations {
 public:
  explicit Durations(const JobHeader& h);
  uint32_t us(uint8_t led, uint8_t value) const;

 private:
  uint64_t scale_[4];  // full_k × gain_k
  bool linear_;
  uint8_t level_;
};

class Planner {
 public:
  // startX: the head's bed X in µm before the first stop (for the `shortest` strategy).
  Planner(const JobHeader& h, CellSource& cells, int32_t startXUm);

  // The next stop in execution order; false when the job is done.
  bool next(Stop& out);
  uint16_t passes() const { return passes_; }

 private:
  struct Compact {
    int16_t hx;
    uint8_t value[4];
  };

  bool openPass();
  bool mergeNext(int32_t& hx, uint8_t value[4]);  // next stop of the pass with a non-zero duration
  void advance(uint8_t led);
  void fillBlock();
  void toStop(int32_t hx, const uint8_t value[4], Stop& out);

  const JobHeader& h_;
  CellSource& cells_;
  Durations dose_;
  uint8_t covered_[kPlannerMaxRows / 8] = {};
  uint16_t scan_ = 0;         // next row that may open a pass
  int32_t hy_ = 0;
  int16_t dyMin_ = 0;
  bool inPass_ = false;
  bool descending_ = false;
  uint16_t passes_ = 0;       // passes that emitted a stop
  bool passEmitted_ = false;
  int32_t curX_;              // bed X of the last stop, µm
  bool live_[4] = {};         // cursor k has a current cell
  uint16_t col_[4] = {};
  uint8_t val_[4] = {};
  uint32_t rng_;
  Compact block_[kRandomBlock];
  uint8_t blockLen_ = 0, blockPos_ = 0;
};

}  // namespace uv
