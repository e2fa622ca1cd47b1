// Encodes a job header and rows of cells as the canonical job text of protocol/job.md, one record at a time.
#pragma once
#include <stdint.h>

#include "job_types.h"

namespace uv {

// Receives each record without '\n' (NUL-terminated, at most 80 bytes).
class RecordSink {
 public:
  virtual void record(const char* text, uint8_t len) = 0;
};

// Feed the header, then every row in order, then finish(). Only one row is held by the caller.
// Format 2 (job.md "Run-length rows") writes a row as `rl` records where they are shorter.
class JobEncoder {
 public:
  explicit JobEncoder(RecordSink& sink, uint8_t format = 1) : sink_(sink), format_(format) {}
  uint8_t format() const { return format_; }

  void header(const JobHeader& h);
  void row(uint16_t rowIndex, const uint8_t* cells, uint16_t cols);
  // One `r` record of a row at a time, for a reader that pulls records: emits the record that
  // starts at or after `column` and moves `column` past it; false when the row has no more.
  bool nextRecord(uint16_t rowIndex, const uint8_t* cells, uint16_t cols, uint16_t& column);
  // Format 2: whether row() writes this row as `rl` records (they are shorter than its `r` ones).
  bool runsShorter(uint16_t rowIndex, const uint8_t* cells, uint16_t cols);
  // One `rl` record of a row at a time, as nextRecord: `column` starts at 0 and is moved past each.
  bool nextRunRecord(uint16_t rowIndex, const uint8_t* cells, uint16_t cols, uint16_t& column);
  void finish();

 private:
  void emit(const char* text, uint8_t len);

  RecordSink& sink_;
  uint32_t crc_ = 0;
  uint8_t format_;
  bool measuring_ = false;  // emit() only counts the bytes, into measured_
  uint32_t measured_ = 0;
};

}  // namespace uv
