// The Mega's state as its lines tell it (protocol/mega.md §4), folded into the snapshot of
// GET /status and the live `status` message (protocol/esp.md). Plain C++.
#pragma once
#include <stdint.h>

#include "dialect_reply.h"
#include "json_writer.h"
#include "job_upload.h"

namespace uv {
namespace esp {

class StatusFold {
 public:
  static constexpr uint32_t kOfflineMs = 5000;  // the Mega reports temperatures every second
  static constexpr uint32_t kFaultMs = 60000;   // how long a FAULT line stays in `faults`
  static constexpr uint8_t kFaults = 8;

  // Every line from the Mega, as it arrives.
  void line(const char* text, uint8_t len, uint32_t nowMs);
  bool online(uint32_t nowMs) const { return heard_ && nowMs - lastHeardMs_ < kOfflineMs; }
  // A job the Mega is running, pausing or receiving: a new one must wait (409).
  bool jobActive() const {
    return job_ == JobState::Running || job_ == JobState::Paused || job_ == JobState::Uploading;
  }
  bool jobRunning() const { return job_ == JobState::Running || job_ == JobState::Paused; }
  // Bumped on every change that a client would see.
  uint32_t changes() const { return changes_; }

  // The snapshot object; `upload` is the ESP's latest upload, or null.
  void write(JsonWriter& w, const UploadProgress* upload, uint8_t clients, uint32_t nowMs) const;

 private:
  void job(const Reply& r);
  // `M850 thermal.limit.<i> <°C>`, from M503's listing or an M850 query: a sensor's soft limit.
  void limit(const char* text, uint8_t len);

  bool heard_ = false;
  uint32_t lastHeardMs_ = 0;
  char firmware_[48] = "";
  bool hasPosition_ = false, hasTemps_ = false, hasProbe_ = false, hasJob_ = false;
  uint8_t limitsKnown_ = 0;  // a bit per sensor whose soft limit the Mega has listed
  int32_t um_[3] = {};
  int16_t deciC_[kSensorCount] = {}, limitDeciC_[kSensorCount] = {};
  ProbeState probe_ = ProbeState::Open;
  JobState job_ = JobState::Idle;
  char jobFile_[32] = "";
  uint32_t stop_ = 0, stops_ = 0;
  struct Fault {
    uint16_t code;
    uint32_t atMs;
  } faults_[kFaults] = {};
  uint8_t faultCount_ = 0;
  uint32_t changes_ = 0;
};

}  // namespace esp
}  // namespace uv
