// Receives a job upload (M28 ... M29) onto the SD card: each record is checked as it arrives and
// written as text under the job's name; its cells also go, row by row, into the cells and index
// files the planner reads. A job that fails any check, or stops before `end`, is deleted whole.
#pragma once
#include <stdint.h>

#include "job_files.h"
#include "dialect_frame.h"
#include "job_verifier.h"
#include "storage.h"

namespace mega {

class JobSpool : private uv::SegmentSink {
 public:
  explicit JobSpool(Storage& sd) : sd_(sd), verifier_(this) {}

  // Opens the files; 0, or 22 (file_error).
  uint8_t begin(const char* name);
  // For a job already on the card (copied there by a PC): builds only the working files, reading
  // the text with prepareStep(). 0, or 21/22.
  uint8_t beginPrepared(const char* name);
  // Reads and checks up to `lines` more records of a prepared job. True at its end (then finish()).
  bool prepareStep(uint8_t lines);
  // One record (without '\n'). Returns 0, or the first error (23 malformed; 22 the card failed);
  // after an error the rest is read and dropped.
  uint8_t record(const char* text, uint8_t len);
  // M29: checks the end of the job. 0 keeps the files; any error deletes them.
  uint8_t finish();
  // Gives up (M112, a second M28): the files are deleted.
  void abandon();

  uint8_t error() const { return error_; }
  uint32_t errorLine() const { return verifier_.errorLine(); }
  const uv::JobHeader& header() const { return verifier_.header(); }
  const char* name() const { return name_; }
  uint32_t bytes() const { return bytes_; }

 private:
  void segment(uint16_t row, uint16_t col, const uint8_t* cells, uint8_t n) override;
  bool closeRow();
  bool writeIndex(uint16_t upTo);
  bool zeros(uint16_t n);
  void fail(uint8_t code);
  void closeAll();

  Storage& sd_;
  uv::JobVerifier verifier_;
  char name_[kFileNameMax + 1] = {};
  FileHandle text_ = -1, cells_ = -1, index_ = -1;
  uint32_t bytes_ = 0;
  uint32_t cellBytes_ = 0;   // size of the cells file so far
  int32_t row_ = -1;          // the row being written
  uint32_t rowOffset_ = 0;
  uint16_t first_ = 0, next_ = 0;  // the row's first non-zero column; the column after its last written cell
  uint16_t last_ = 0;               // the row's last non-zero column
  bool started_ = false;            // the row has a non-zero cell
  uint16_t indexed_ = 0;      // rows with an index entry written
  uint8_t error_ = 0;
  bool prepared_ = false;  // the text was already on the card: never rewrite or delete it
  LineReader* reader_ = nullptr;
  alignas(4) uint8_t readerMem_[sizeof(LineReader)];
};

}  // namespace mega
