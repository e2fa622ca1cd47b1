// Stream mode (M828, protocol/mega.md): each record is checked as it arrives, its cells go into a
// bounded buffer, and the planner plans the stops no later row can change; the runner exposes them
// as they come. Rows are freed as soon as nothing still to come can read them.
#pragma once
#include <stdint.h>

#include "job_verifier.h"
#include "planner.h"
#include "stop_source.h"
#include "stream_cells.h"

namespace mega {

constexpr uint8_t kRecordWaits = 0xff;  // record(): no room yet, offer it again later

class StreamJob : public StopSource, private uv::SegmentSink {
 public:
  StreamJob(uint8_t* buffer, uint16_t size, const uv::MotionModel& machine)
      : verifier_(this), cells_(buffer, size), machine_(machine) {}
  ~StreamJob();

  // One record (without '\n'): 0 taken; 23 (malformed) and the like; kRecordWaits if its cells do
  // not fit the buffer yet; 28 if they never can (the next stops need more rows than it holds).
  uint8_t record(const char* text, uint8_t len);
  // M29: 0, or why the stream failed (the first record error, 24, 25).
  uint8_t finish();
  uint8_t error() const { return error_; }
  uint32_t errorLine() const { return verifier_.errorLine(); }
  bool headerReady() const { return planner_ != nullptr || scan_ != nullptr; }
  const uv::JobHeader& header() const { return verifier_.header(); }
  uint16_t heldCells() const { return cells_.cells(); }

  NextStop next(uint32_t index, uv::Stop& out) override;
  // A scan or mixed job: its passes on the move done or under way, and the stops handed out.
  uint32_t count() const override { return scan_ ? scan_->run.passes() + (scan_->run.idle() ? 0u : 1u) + planned_ : planned_; }
  bool complete() const override { return done_; }
  ScanRun::Step scanStep(Motion& motion, PrintheadLink& head, uint32_t nowUs) override;
  uint8_t scanError() const override { return error_ ? error_ : scan_ ? scan_->run.error() : 0; }

 private:
  void segment(uint16_t row, uint16_t col, const uint8_t* cells, uint8_t n) override;
  uint8_t fail(uint8_t code) { return error_ ? error_ : (error_ = code); }

  uv::JobVerifier verifier_;
  StreamCells cells_;
  uv::MotionModel machine_;
  void freeRows(int32_t lowest) { cells_.freeBelow(static_cast<uint16_t>(lowest)); }
  int32_t lowestRowNeeded() const { return scan_ ? scan_->planner.lowestRowNeeded() : planner_->lowestRowNeeded(); }

  uv::Planner* planner_ = nullptr;
  ScanJob* scan_ = nullptr;  // a scan or mixed job's, in the stop planner's place
  static constexpr size_t kPlannerBytes = sizeof(uv::Planner) > sizeof(ScanJob) ? sizeof(uv::Planner) : sizeof(ScanJob);
  alignas(alignof(uv::Planner) > alignof(ScanJob) ? alignof(uv::Planner) : alignof(ScanJob)) uint8_t plannerMem_[kPlannerBytes];
  uint32_t planned_ = 0;
  uint16_t known_ = 0;
  bool done_ = false;
  bool starved_ = false;  // the runner asked for a stop the planner could not give yet
  uint8_t error_ = 0;
};

}  // namespace mega
