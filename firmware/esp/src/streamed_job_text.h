// The job text of a spooled POST /print body, made again record by record as the upload pulls
// it, so the ESP's flash holds only the body: a 1.2 MB body and its up to 0.63 MB of job text
// would not both fit next to the app on a 4 MB ESP-12E or ESP32. The body was checked whole
// before the job was accepted (JobConversion); a body that reads differently now (flash trouble)
// ends the upload, which M29 would catch anyway.
#pragma once
#include <stdint.h>
#include <string.h>

#include "grid_rows.h"
#include "job_encoder.h"
#include "job_upload.h"

namespace uv {
namespace esp {

// Reader: int read(), and bool rewind() to read the body from its start again.
template <class Reader>
class StreamedJobText : public JobText, private RecordSink {
 public:
  // `cells` holds one row (kJobMaxSide bytes); `h` is the header the body was accepted with, and
  // `format` the job format it was counted in (job.md): in format 2 a row goes as `rl` records
  // where they are shorter, still one record at a time.
  StreamedJobText(Reader& body, const JobHeader& h, uint8_t* cells, uint8_t format = 1)
      : body_(body), rows_(body), header_(h), encoder_(*this, format), cells_(cells) {}

  bool rewind() override {
    ok_ = body_.rewind();
    if (!ok_) return false;
    GridDataShape shape = rows_.open();
    ok_ = shape.present && shape.isArray;
    held_ = 0;
    taken_ = 0;
    row_ = 0;
    column_ = header_.cols;  // no row read yet
    ended_ = false;
    encoder_.header(header_);  // its records wait in held_
    return ok_;
  }

  int next(char* buf, uint8_t size) override {
    if (!ok_) return -1;
    while (taken_ == held_) {  // make the next record
      taken_ = held_ = 0;
      if (ended_) return -1;
      if (column_ < header_.cols && nextRecord()) break;
      if (row_ == header_.rows) {
        RequestError e{};
        ok_ = rows_.finish(e);
        if (!ok_) return -1;
        encoder_.finish();
        ended_ = true;
        break;
      }
      RequestError e{};
      ok_ = rows_.next(row_, header_, cells_, e);
      if (!ok_) return -1;
      row_++;
      column_ = 0;
      runs_ = encoder_.runsShorter(static_cast<uint16_t>(row_ - 1), cells_, header_.cols);
    }
    // One record out of what is held, NUL-terminated.
    const char* text = held(taken_);
    uint8_t len = static_cast<uint8_t>(strlen(text));
    if (len + 1u > size) {
      ok_ = false;
      return -1;
    }
    memcpy(buf, text, len + 1u);
    taken_++;
    return len;
  }

  bool ok() const override { return ok_; }

 private:
  bool nextRecord() {
    const uint16_t row = static_cast<uint16_t>(row_ - 1);
    return runs_ ? encoder_.nextRunRecord(row, cells_, header_.cols, column_) : encoder_.nextRecord(row, cells_, header_.cols, column_);
  }
  // The encoder's records: the header's ten at once, else one at a time.
  void record(const char* text, uint8_t len) override {
    if (held_ == kHeld) return;
    memcpy(records_[held_], text, len);
    records_[held_][len] = 0;
    held_++;
  }
  const char* held(uint8_t i) const { return records_[i]; }

  static constexpr uint8_t kHeld = 12;
  Reader& body_;
  GridRows<Reader> rows_;
  JobHeader header_;
  JobEncoder encoder_;
  uint8_t* cells_;
  char records_[kHeld][84];
  uint8_t held_ = 0, taken_ = 0;
  uint16_t row_ = 0;      // rows read so far
  uint16_t column_ = 0;   // where the next record of the current row starts
  bool runs_ = false;     // the current row goes as `rl` records
  bool ended_ = false;
  bool ok_ = false;
};

}  // namespace esp
}  // namespace uv
