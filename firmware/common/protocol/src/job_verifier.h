// Streaming verifier of job text (protocol/job.md): record syntax, order, bounds and the whole-job CRC.
#pragma once
#include <stdint.h>

#include "job_types.h"

namespace uv {

// Receives the cells of each record once the whole record has verified, decoded, as pieces of at
// most kJobMaxCellsPerRecord cells in column order (an `rl` record of format 2 may give several).
class SegmentSink {
 public:
  virtual void segment(uint16_t row, uint16_t col, const uint8_t* cells, uint8_t n) = 0;
};

uint8_t hexCell(const char* hex, uint8_t index);

// The bytes the pieces of a record take in a store that keeps `head` bytes and the cells of each
// piece, leaving out the pieces of a zero run: an upper bound for a record that is malformed.
uint16_t recordPieceBytes(const char* record, uint8_t len, uint8_t head);

// Feed records one at a time, without '\n'. The first error sticks. RAM: sizeof(JobVerifier).
class JobVerifier {
 public:
  explicit JobVerifier(SegmentSink* sink = nullptr) : sink_(sink) {}

  // Returns 0 or an ErrorCode (23 malformed, 24 hash, 25 incomplete).
  uint8_t push(const char* record, uint8_t len);
  uint8_t finish();

  uint8_t error() const { return error_; }
  uint32_t errorLine() const { return lineNo_; }
  bool complete() const { return ended_ && !error_; }
  bool headerDone() const { return index_ >= 10; }
  const JobHeader& header() const { return h_; }
  uint8_t format() const { return format_; }

 private:
  uint8_t fail(uint8_t code) { return error_ = code; }
  bool headerRecord(const char* p, const char* end);
  bool segment(const char* p, const char* end);
  bool runs(const char* p, const char* end);
  bool claim(int32_t row, int32_t col, uint16_t cells);
  uint8_t endRecord(const char* p, const char* end);

  SegmentSink* sink_;
  JobHeader h_ = {};
  uint32_t crc_ = 0;
  uint32_t lineNo_ = 0;
  int32_t prevRow_ = -1;
  uint16_t prevEnd_ = 0;
  uint8_t index_ = 0;
  uint8_t format_ = 1;  // `uvj 1` or `uvj 2`: 2 may carry `rl` records
  uint8_t error_ = 0;
  bool ended_ = false;
};

}  // namespace uv
