// Stream mode: records checked on arrival, cells in a bounded buffer, stops planned as rows arrive.
#include "stream_job.h"

#include <new>
#include <string.h>

#include "error_codes.h"

namespace mega {

namespace {
constexpr uint8_t kSegmentHead = 5;
}  // namespace

StreamJob::~StreamJob() {
  if (planner_) planner_->~Planner();
  if (scan_) scan_->~ScanJob();
}

void StreamJob::segment(uint16_t row, uint16_t col, const uint8_t* cells, uint8_t n) {
  // A piece of a zero run is left out (a cell no segment holds reads 0); room was made before the
  // record was taken, for every other piece.
  bool zero = true;
  for (uint8_t i = 0; i < n && zero; i++) zero = cells[i] == 0;
  if (!zero) cells_.add(row, col, cells, n);
  if (row > known_) known_ = row;     // a record of a later row: every row below it has arrived
}

uint8_t StreamJob::record(const char* text, uint8_t len) {
  if (error_) return error_;  // after a failure the rest is only read
  const uint16_t room = uv::recordPieceBytes(text, len, kSegmentHead);
  if (room && static_cast<uint32_t>(cells_.used()) + room > cells_.size()) {
    if (planner_ || scan_) freeRows(lowestRowNeeded());
    if (static_cast<uint32_t>(cells_.used()) + room > cells_.size()) {
      // Full. If the planner waits for rows to plan the next stop, they can never come: E28.
      return starved_ ? fail(uv::kStreamOverflow) : kRecordWaits;
    }
  }
  uint8_t err = verifier_.push(text, len);
  if (err) return fail(err);
  if (!planner_ && !scan_ && verifier_.headerDone()) {
    const uv::Strategy s = verifier_.header().strategy;
    if (s != uv::Strategy::Scan && s != uv::Strategy::Mixed) {
      planner_ = new (plannerMem_) uv::Planner(verifier_.header(), cells_, machine_);
    } else {
      scan_ = new (plannerMem_) ScanJob(verifier_.header(), cells_, machine_);
    }
  }
  if (verifier_.complete()) known_ = verifier_.header().rows;
  if (planner_) {
    planner_->setKnownRows(known_);
    if (!planner_->supported()) return fail(uv::kJobMalformed);
  }
  if (scan_) {
    scan_->planner.setKnownRows(known_);
    if (!scan_->planner.supported()) return fail(uv::kJobMalformed);
  }
  return 0;
}

uint8_t StreamJob::finish() {
  if (error_) return error_;
  uint8_t err = verifier_.finish();
  if (err) return fail(err);
  if (planner_) planner_->setKnownRows(verifier_.header().rows);
  if (scan_) scan_->planner.setKnownRows(verifier_.header().rows);
  return 0;
}

ScanRun::Step StreamJob::scanStep(Motion& motion, PrintheadLink& head, uint32_t nowUs) {
  if (error_) return ScanRun::Step::Failed;
  const ScanRun::Step s = scan_->run.poll(motion, head, verifier_.header(), nowUs);
  if (s == ScanRun::Step::Starved || s == ScanRun::Step::PassDone) freeRows(lowestRowNeeded());
  starved_ = s == ScanRun::Step::Starved;
  if (s == ScanRun::Step::End) done_ = true;
  return s;
}

NextStop StreamJob::next(uint32_t, uv::Stop& out) {
  if (error_) return NextStop::Error;
  if (scan_) {
    // A mixed job's stop pass: its stops one at a time, then its passes on the move again.
    if (!scan_->planner.nextStop(out)) return NextStop::Scan;
    planned_++;
    freeRows(lowestRowNeeded());
    return NextStop::Stop;
  }
  if (!planner_) {
    starved_ = true;
    return NextStop::Wait;
  }
  if (planner_->next(out)) {
    starved_ = false;
    planned_++;
    freeRows(lowestRowNeeded());
    return NextStop::Stop;
  }
  if (planner_->starved()) {
    starved_ = true;
    freeRows(lowestRowNeeded());
    return NextStop::Wait;
  }
  done_ = true;
  return NextStop::End;
}

}  // namespace mega
