// A POST /print body from its spool to its answer (protocol/esp.md): the header through the JSON
// library with gridData filtered out, then the rows a share at a time, so the hub's loop keeps
// serving the Mega and its clients; then 202 and the upload, or 400/413 naming the field. The
// ESP and the host hub run this same code over their own file and JSON library.
//
// Body: the Reader of grid_rows.h with rewind() and close(). HeaderParse: a callable
// `int parse(Body&, F use)` that parses the whole body leaving gridData's contents out, calls
// `use(view)` with a JSON view of the result and returns 0, or 400 (not JSON) / 413 (too big).
#pragma once
#include <stdint.h>
#include <string.h>

#include <new>

#include "bridge.h"
#include "http_rules.h"
#include "job_conversion.h"
#include "json_writer.h"
#include "streamed_job_text.h"

namespace uv {
namespace esp {

enum class Intake : uint8_t { Working, Accepted, Refused };

template <class Body, class HeaderParse>
class PrintIntake {
 public:
  static constexpr uint32_t kCellsPerStep = 8192;  // a few ms on an ESP8266

  PrintIntake(Body& body, Bridge& bridge, HeaderParse parse) : body_(body), bridge_(bridge), parse_(parse) {}

  // The whole body is spooled; the Mega was admitted for it (Bridge::admitPrint).
  void begin() {
    stage_ = Stage::Header;
    status_ = 0;
  }
  bool busy() const { return stage_ != Stage::Idle; }

  // One share of the work. Accepted: the upload has begun with `id` (call nextId once only then).
  template <class NextId>
  Intake step(NextId nextId) {
    if (stage_ == Stage::Header) return header();
    if (stage_ != Stage::Rows) return Intake::Refused;
    for (uint32_t cells = 0; cells < kCellsPerStep; cells += conversion().header().cols) {
      ConversionStep s = conversion().step();
      if (s == ConversionStep::More) continue;
      if (s == ConversionStep::Failed) return refuse(conversion().error());
      JobHeader h = conversion().header();
      uint32_t bytes = conversion().textBytes();
      bool paced = conversion().paced();
      uint8_t format = conversion().format();
      conversion().~JobConversion();
      uint32_t id = nextId();
      if (textMade_) text().~StreamedJobText();
      new (textMem_) StreamedJobText<Body>(body_, h, cells_, format);
      textMade_ = true;
      JsonWriter w(response_, sizeof response_);
      w.beginObject().key("job").beginObject().key("id").number(id).key("state").string("uploading");
      w.key("cells").number(static_cast<int64_t>(h.cols) * h.rows).endObject().endObject();
      status_ = 202;
      stage_ = Stage::Idle;
      bridge_.startUpload(id, text(), bytes, paced);
      return Intake::Accepted;
    }
    return Intake::Working;
  }

  // DELETE /print while the body is being checked.
  void cancel() {
    if (stage_ == Stage::Rows) conversion().~JobConversion();
    RequestError e{409, kCancelledCode, "", ""};
    strncpy(e.message, kCancelledMessage, sizeof e.message - 1);
    refuse(e);
  }

  // The upload is over (or never began): the spool's file is let go of, so that the ESP's network
  // task may write the next body into it (loop_desk.h).
  void closeBody() { body_.close(); }

  uint16_t status() const { return status_; }
  const char* response() const { return response_; }

 private:
  enum class Stage : uint8_t { Idle, Header, Rows };

  Intake header() {
    if (!body_.rewind()) return refuse({503, "spool_failed", "", "the hub could not read the job back"});
    // The format the Mega reads, fixed for the job: its size is counted in it (the upload's
    // bytesTotal) and its text made in it again at each attempt.
    new (conversionMem_) JobConversion<Body>(body_, nothing_, cells_, bridge_.jobFormat());
    bool accepted = false;
    int err = parse_(body_, [&](const auto& view) {
      if (!body_.rewind()) return;
      accepted = conversion().begin(view);
    });
    if (err) {
      conversion().~JobConversion();
      return refuse(err == 413 ? RequestError{400, "bad_job", "", "too many or too large fields"} : RequestError{400, "bad_json", "", "not JSON, or it stops early"});
    }
    if (!accepted) {
      RequestError e = conversion().error();
      conversion().~JobConversion();
      if (!e.status) e = {503, "spool_failed", "", "the hub could not read the job back"};
      return refuse(e);
    }
    stage_ = Stage::Rows;
    return Intake::Working;
  }

  Intake refuse(const RequestError& e) {
    JsonWriter w(response_, sizeof response_);
    writeError(w, e.code, e.message, e.path);
    status_ = e.status;
    stage_ = Stage::Idle;
    body_.close();
    bridge_.release();
    return Intake::Refused;
  }

  struct NullSink : RecordSink {
    void record(const char*, uint8_t) override {}
  };
  JobConversion<Body>& conversion() { return *reinterpret_cast<JobConversion<Body>*>(conversionMem_); }
  StreamedJobText<Body>& text() { return *reinterpret_cast<StreamedJobText<Body>*>(textMem_); }

  Body& body_;
  Bridge& bridge_;
  HeaderParse parse_;
  Stage stage_ = Stage::Idle;
  uint16_t status_ = 0;
  char response_[kErrorJsonBytes];  // a 400 naming any field fits whole (and a 202 easily)
  uint8_t cells_[kJobMaxSide];  // one row: the check's, then the upload's
  NullSink nothing_;
  alignas(JobConversion<Body>) uint8_t conversionMem_[sizeof(JobConversion<Body>)];
  alignas(StreamedJobText<Body>) uint8_t textMem_[sizeof(StreamedJobText<Body>)];
  bool textMade_ = false;
};

}  // namespace esp
}  // namespace uv
