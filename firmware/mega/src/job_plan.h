// Plans a spooled job into its stop file (name~s), a few stops each main-loop pass, so the host
// links and the rest of the Mega keep running while it works. A scan or mixed job is planned a pass
// at a time for its count (a mixed job's stops count one each) and time; they are planned again as
// they run (card_scan.h), a scan job's from what planning here kept of each pass (kept_pass.h).
#pragma once
#include <stdint.h>

#include "config.h"
#include "planner.h"
#include "scan.h"
#include "sd_cells.h"
#include "stop_file.h"
#include "storage.h"

namespace mega {

// The machine the planners see, from the settings, with the head starting at (x, y) µm and the
// printhead link at linkBaud (PrintheadLink::jobBaud() when a job is planned; a card job's recorded
// speed when it runs). Jobs on the card are planned from the origin, so they plan the same whenever
// they run. X and Y go no faster than speed.travel, nor than kMaxStepRate steps/s.
uv::MotionModel plannerMachine(const Config& config, int32_t x, int32_t y, uint32_t linkBaud);

class JobPlan {
 public:
  JobPlan(Storage& sd, const uv::JobHeader& header, const uv::MotionModel& machine);
  ~JobPlan();

  // Opens the files; 0 or 22 (file_error). `name` is the job's.
  uint8_t begin(const char* name);
  // Plans up to `stops` more (a scan job: one pass). Returns true once finished (check error()).
  bool step(uint16_t stops);
  uint8_t error() const { return error_; }
  uint32_t planned() const { return count_; }

 private:
  void close();
  bool finish(uint64_t estimateUs);
  bool stepScan();
  static bool passEvent(void* ctx, uint32_t& t, uint8_t& m);

  Storage& sd_;
  uv::JobHeader header_;
  uv::MotionModel machine_;
  FileHandle cells_ = -1, index_ = -1, stops_ = -1;
  SdCellsWith<uv::kPlannerCursors>* source_ = nullptr;
  uv::Planner* planner_ = nullptr;
  uv::ScanPlanner* scan_ = nullptr;  // a scan job's, in the stop planner's place
  uv::PlanClock clock_;
  uint32_t count_ = 0;
  uint32_t passUs_ = 0;  // a scan pass's last event, µs after its start mark
  uint8_t error_ = 0;
  bool done_ = false;
  // The planner and its cursors live here, only while planning.
  alignas(alignof(SdCellsWith<uv::kPlannerCursors>)) uint8_t sourceMem_[sizeof(SdCellsWith<uv::kPlannerCursors>)];
  static_assert(sizeof(uv::ScanPlanner) <= sizeof(uv::Planner), "the scan planner takes the stop planner's place");
  alignas(alignof(uv::Planner)) uint8_t plannerMem_[sizeof(uv::Planner)];
};

}  // namespace mega
