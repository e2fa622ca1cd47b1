// A scan or mixed job on the card (issues 19, 28): its passes planned again from the job's working
// files (~c, ~i) as they run, one at a time, by the scan planner that planned them at M29
// (job_plan.h), a scan job's from what planning kept of each pass then (kept_pass.h: no pass is laid
// out or walked for the link again before it runs), and run by ScanRun, or stop by stop by the job
// runner (a mixed job's stop pass). A step that must run again (after a pause, a fault or a reset) is found by planning the job from its
// start and passing over the steps done (passes, and a mixed job's stops), without light.
#pragma once
#include <stdint.h>

#include "job_types.h"
#include "scan_run.h"
#include "sd_cells.h"
#include "stop_source.h"
#include "storage.h"

namespace mega {

class CardScan final : public StopSource {
 public:
  // `kept`: the passes planning kept in the index file (readScanHeader): `passes` for a scan job, 0
  // for a mixed one.
  CardScan(Storage& sd, const uv::JobHeader& h, const uv::MotionModel& m, uint32_t passes, uint32_t kept)
      : sd_(sd), header_(h), machine_(m), passes_(passes), keptCount_(kept) {}
  ~CardScan();

  // Opens the job's working files; 0 or 22 (file_error, also when the index lacks its kept passes).
  uint8_t open(const char* name);
  // The next pass to run is pass `done` (0-based): if the planner is not just before it, it plans
  // the job again from its start and passes over the first `done`, a pass each scanStep().
  void seek(uint32_t done);

  // A mixed job's stop pass (after scanStep() said Stops): its next stop, which counts as step
  // `done` once confirmed; false at the pass's end, or while passes done before are passed over.
  bool nextStop(uv::Stop& out);
  NextStop next(uint32_t, uv::Stop&) override { return NextStop::Scan; }
  uint32_t count() const override { return passes_; }
  bool complete() const override { return true; }
  ScanRun::Step scanStep(Motion& motion, PrintheadLink& head, uint32_t nowUs) override;
  uint8_t scanError() const override { return error_ ? error_ : job_ ? job_->run.error() : 0; }

 private:
  void release();
  // Pass `pass` as planning kept it, from the index file, or null (none kept: the planner lays it
  // out and searches). A read that fails sets error_.
  const uv::KeptPass* keptOf(uint32_t pass);

  Storage& sd_;
  uv::JobHeader header_;
  uv::MotionModel machine_;
  uint32_t passes_;
  uint32_t keptCount_;
  // The last pass read, and its number (the run asks each poll until the pass opens).
  uv::KeptPass kept_;
  uint32_t keptPass_ = 0xffffffffu;
  FileHandle cells_ = -1, index_ = -1;
  SdCellsWith<uv::kScanCursors>* source_ = nullptr;
  ScanJob* job_ = nullptr;
  uint32_t opened_ = 0;  // steps the planner has finished (run or passed over): passes on the move, stops
  uint32_t skip_ = 0;    // steps still to pass over before the next runs
  uint8_t error_ = 0;
  alignas(alignof(SdCellsWith<uv::kScanCursors>)) uint8_t sourceMem_[sizeof(SdCellsWith<uv::kScanCursors>)];
  alignas(alignof(ScanJob)) uint8_t jobMem_[sizeof(ScanJob)];
};

}  // namespace mega
