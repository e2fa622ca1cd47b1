// Turns a spooled POST /print body into the job text of protocol/job.md, one row per step(), so
// the ESP's loop stays responsive while a 1.2 MB body converts. The header comes from the JSON
// library (a view with gridData filtered out), the rows from grid_rows.h over the same file.
#pragma once
#include <stdint.h>

#include "grid_rows.h"
#include "job_encoder.h"
#include "print_request.h"

namespace uv {
namespace esp {

// Counts the job text as it goes to its real sink: bytesTotal of the upload.
class CountingSink : public RecordSink {
 public:
  explicit CountingSink(RecordSink& out) : out_(out) {}
  void record(const char* text, uint8_t len) override {
    bytes_ += len + 1u;
    lines_++;
    out_.record(text, len);
  }
  uint32_t bytes() const { return bytes_; }
  uint32_t lines() const { return lines_; }

 private:
  RecordSink& out_;
  uint32_t bytes_ = 0, lines_ = 0;
};

enum class ConversionStep : uint8_t { More, Done, Failed };

template <class Reader>
class JobConversion {
 public:
  // `cells` holds one row: kJobMaxSide bytes; `format` is the job format written (job.md).
  JobConversion(Reader& body, RecordSink& out, uint8_t* cells, uint8_t format = 1)
      : rows_(body), sink_(out), encoder_(sink_, format), cells_(cells) {}

  // `root` is the body parsed without gridData's contents; `body` must be at the file's start.
  template <class J>
  bool begin(const J& root) {
    GridDataShape shape = rows_.open();
    if (!validateHeader(root, shape, header_, paced_, error_)) return false;
    encoder_.header(header_);
    return true;
  }

  // Converts the next row, or ends the job once all rows are in.
  ConversionStep step() {
    if (next_ == header_.rows) {
      if (!rows_.finish(error_)) return ConversionStep::Failed;
      encoder_.finish();
      return ConversionStep::Done;
    }
    if (!rows_.next(next_, header_, cells_, error_)) return ConversionStep::Failed;
    encoder_.row(next_, cells_, header_.cols);
    next_++;
    return ConversionStep::More;
  }

  const JobHeader& header() const { return header_; }
  // Run the job paced: the body said "paced": true.
  bool paced() const { return paced_; }
  const RequestError& error() const { return error_; }
  uint32_t textBytes() const { return sink_.bytes(); }
  uint32_t textLines() const { return sink_.lines(); }
  uint16_t rowsDone() const { return next_; }
  uint8_t format() const { return encoder_.format(); }

 private:
  GridRows<Reader> rows_;
  CountingSink sink_;
  JobEncoder encoder_;
  uint8_t* cells_;
  JobHeader header_{};
  RequestError error_{};
  uint16_t next_ = 0;
  bool paced_ = false;
};

}  // namespace esp
}  // namespace uv
