// A scan job on the card: see card_scan.h.
#include "card_scan.h"

#include <new>

#include "error_codes.h"
#include "job_files.h"
#include "kept_pass.h"
#include "le_bytes.h"

namespace mega {

CardScan::~CardScan() {
  release();
  if (cells_ >= 0) sd_.close(cells_);
  if (index_ >= 0) sd_.close(index_);
}

void CardScan::release() {
  if (job_) job_->~ScanJob();
  if (source_) source_->~SdCellsWith();
  job_ = nullptr;
  source_ = nullptr;
}

uint8_t CardScan::open(const char* name) {
  if (!openCellFiles(sd_, name, cells_, index_)) return uv::kFileError;
  // A scan job's kept passes, one a pass, all there: else the files changed since M29.
  if (keptCount_ && (keptCount_ != passes_ || sd_.size(index_) < keptPassAt(header_.rows, keptCount_))) return uv::kFileError;
  return 0;
}

const uv::KeptPass* CardScan::keptOf(uint32_t pass) {
  if (pass >= keptCount_) return nullptr;
  if (pass != keptPass_) {
    char b[kKeptPassBytes];
    if (!sd_.seek(index_, keptPassAt(header_.rows, pass)) || sd_.read(index_, b, sizeof b) != sizeof b || !getKeptPass(b, kept_)) {
      error_ = uv::kFileError;
      return nullptr;
    }
    keptPass_ = pass;
  }
  return &kept_;
}

void CardScan::seek(uint32_t done) {
  if (job_ && opened_ == done && skip_ == 0 && job_->run.idle()) return;  // just before it already
  release();
  source_ = new (sourceMem_) SdCellsWith<uv::kScanCursors>(sd_, cells_, index_);
  job_ = new (jobMem_) ScanJob(header_, *source_, machine_);
  opened_ = 0;
  skip_ = done;
  error_ = 0;
}

ScanRun::Step CardScan::scanStep(Motion& motion, PrintheadLink& head, uint32_t nowUs) {
  if (!job_) seek(0);
  if (skip_) {  // a step done before: a pass planned (a mixed job's, its events walked), or a stop; nothing lit
    uv::Stop stop;
    if (job_->planner.inStopPass() && job_->planner.nextStop(stop)) {
      skip_--;
      opened_++;
      return ScanRun::Step::Busy;
    }
    uv::ScanPass p;
    const uv::KeptPass* kept = keptOf(opened_);
    if (error_) return ScanRun::Step::Failed;
    if (!job_->planner.nextPass(p, kept)) {
      if (job_->planner.pricing()) return ScanRun::Step::Busy;  // a band priced a pass a call
      error_ = uv::kFileError;  // fewer passes than planned at M29: the files changed
      return ScanRun::Step::Failed;
    }
    if (p.stops) return ScanRun::Step::Busy;  // its stops are passed over one a call
    // A kept pass (a scan job's) leaves nothing the next one reads: it opens from its own record, and
    // walking its events (some 50 µs each on the Mega) would hold the main loop for nothing. A mixed
    // job's pass is walked to its end, as its run walked it.
    uint32_t t;
    uint8_t m;
    while (!kept && job_->planner.nextEvent(t, m)) {
    }
    skip_--;
    opened_++;
    return ScanRun::Step::Busy;
  }
  if (job_->planner.inStopPass()) return ScanRun::Step::Stops;  // a mixed job's stop pass, part done before
  const uv::KeptPass* kept = keptOf(opened_);  // the pass that opens next, or the one running
  if (error_) return ScanRun::Step::Failed;
  const ScanRun::Step s = job_->run.poll(motion, head, header_, nowUs, kept);
  if (s == ScanRun::Step::PassDone) opened_++;
  if (s == ScanRun::Step::End && opened_ < keptCount_) {  // a kept pass not found: the files changed since M29
    error_ = uv::kFileError;
    return ScanRun::Step::Failed;
  }
  if (source_->failed()) {
    error_ = uv::kFileError;
    return ScanRun::Step::Failed;
  }
  return s;
}

bool CardScan::nextStop(uv::Stop& out) {
  if (!job_ || skip_ || !job_->planner.nextStop(out) || source_->failed()) return false;
  opened_++;
  return true;
}

}  // namespace mega
