// Trapezoidal move times and the per-stop clock of protocol/planner.md "Time model", in integer µs.
#pragma once
#include <stdint.h>

#include "job_types.h"

namespace uv {

struct Machine {
  uint32_t vmaxUmS[2];
  uint32_t accelUmS2[2];
  uint32_t settleUs;
  uint32_t overheadUs;
  int32_t startUm[2];
};

struct Stop {
  int32_t hx, hy;   // head position in cells
  uint32_t us[4];   // per LED
};

uint64_t isqrt64(uint64_t n);
// Time in µs to move d µm on one axis, from rest to rest.
uint32_t moveTimeUs(uint32_t d, uint32_t v, uint32_t a);

// One stop's time from the previous head position (bed µm): the slower axis's move, settle if
// it moved, the per-stop overhead and the longest LED duration.
uint32_t stopCostUs(const Machine& m, int32_t fromX, int32_t fromY, int32_t toX, int32_t toY, uint32_t longestUs);

// Adds up the estimate stop by stop, as the planner emits them.
class PlanClock {
 public:
  PlanClock(const JobHeader& h, const Machine& m) : h_(h), m_(m), x_(m.startUm[0]), y_(m.startUm[1]) {}
  void add(const Stop& s);
  uint64_t totalUs() const { return total_; }
  uint64_t travelUm(uint8_t axis) const { return travel_[axis]; }

 private:
  const JobHeader& h_;
  const Machine& m_;
  int32_t x_, y_;
  uint64_t total_ = 0;
  uint64_t travel_[2] = {0, 0};
};

}  // namespace uv
