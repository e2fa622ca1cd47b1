// Stream mode: records checked on arrival, cells in a bounded buffer, stops planned as rows arrive.
#include "stream_job.h"

#include <new>
#include <string.h>

#include "error_codes.h"

namespace mega {

namespace {
// The cells a record brings: `r <row> <col> <hex>` carries hex/2 of them; others none.
uint8_t recordCells(const char* text, uint8_t len) {
  if (len < 2 || text[0] != 'r' || text[1] != ' ') return 0;
  uint8_t spaces = 0, i = 0;
  while (i < len && spaces < 3) spaces = static_cast<uint8_t>(spaces + (text[i++] == ' '));
  return static_cast<uint8_t>((len - i) / 2);
}
constexpr uint8_t kSegmentHead = 5;
}  // namespace

StreamJob::~StreamJob() {
  if (planner_) planner_->~Planner();
}

void StreamJob::segment(uint16_t row, uint16_t col, const char* hex, uint8_t cells) {
  uint8_t buf[uv::kJobMaxCellsPerRecord];
  for (uint8_t i = 0; i < cells; i++) buf[i] = uv::hexCell(hex, i);
  cells_.add(row, col, buf, cells);  // room was made before the record was taken
  if (row > known_) known_ = row;     // a record of a later row: every row below it has arrived
}

uint8_t StreamJob::record(const char* text, uint8_t len) {
  if (error_) return error_;  // after a failure the rest is only read
  uint8_t n = recordCells(text, len);
  if (n && cells_.used() + kSegmentHead + n > cells_.size()) {
    if (planner_) cells_.freeBelow(static_cast<uint16_t>(planner_->lowestRowNeeded()));
    if (cells_.used() + kSegmentHead + n > cells_.size()) {
      // Full. If the planner waits for rows to plan the next stop, they can never come: E28.
      return starved_ ? fail(uv::kStreamOverflow) : kRecordWaits;
    }
  }
  uint8_t err = verifier_.push(text, len);
  if (err) return fail(err);
  // This firmware plans stops only: a scan job ends with its header, before any light.
  if (!planner_ && verifier_.headerDone() && verifier_.header().strategy == uv::Strategy::Scan) return fail(uv::kScanUnsupported);
  if (!planner_ && verifier_.headerDone()) planner_ = new (plannerMem_) uv::Planner(verifier_.header(), cells_, machine_);
  if (planner_) {
    if (verifier_.complete()) known_ = verifier_.header().rows;
    planner_->setKnownRows(known_);
    if (!planner_->supported()) return fail(uv::kJobMalformed);
  }
  return 0;
}

uint8_t StreamJob::finish() {
  if (error_) return error_;
  uint8_t err = verifier_.finish();
  if (err) return fail(err);
  if (planner_) planner_->setKnownRows(verifier_.header().rows);
  return 0;
}

NextStop StreamJob::next(uint32_t, uv::Stop& out) {
  if (error_) return NextStop::Error;
  if (!planner_) {
    starved_ = true;
    return NextStop::Wait;
  }
  if (planner_->next(out)) {
    starved_ = false;
    planned_++;
    cells_.freeBelow(static_cast<uint16_t>(planner_->lowestRowNeeded()));
    return NextStop::Stop;
  }
  if (planner_->starved()) {
    starved_ = true;
    cells_.freeBelow(static_cast<uint16_t>(planner_->lowestRowNeeded()));
    return NextStop::Wait;
  }
  done_ = true;
  return NextStop::End;
}

}  // namespace mega
