// Folds the Mega's reports into the ESP's status snapshot.
#include "status_fold.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dialect_command.h"

namespace uv {
namespace esp {

namespace {

const char* const kProbeNames[] = {"triggered", "open", "alarm", "deployed", "stowed"};

// The value of ` key=` in a JOB: line's fields, up to the next space; its length, or -1.
int field(const char* text, uint8_t len, const char* key, const char** value) {
  size_t k = strlen(key);
  for (uint8_t i = 0; i + k + 1 < len + 1u; i++) {
    if ((i == 0 || text[i - 1] == ' ') && strncmp(text + i, key, k) == 0 && text[i + k] == '=') {
      const char* v = text + i + k + 1;
      const char* e = v;
      while (e < text + len && *e != ' ') e++;
      *value = v;
      return static_cast<int>(e - v);
    }
  }
  return -1;
}

}  // namespace

void StatusFold::line(const char* text, uint8_t len, uint32_t nowMs) {
  heard_ = true;  // going on- or offline is news the bridge sees by asking online()
  lastHeardMs_ = nowMs;
  Reply r{};
  if (!parseReply(text, len, r)) return;
  switch (r.kind) {
    case ReplyKind::Firmware:
      snprintf(firmware_, sizeof firmware_, "%.*s", r.textLen, r.text);
      changes_++;
      break;
    case ReplyKind::Position:
      hasPosition_ = true;
      memcpy(um_, r.um, sizeof um_);
      break;
    case ReplyKind::Temps:
      hasTemps_ = true;
      memcpy(deciC_, r.deciC, sizeof deciC_);
      break;
    case ReplyKind::Other: limit(r.text, r.textLen); break;
    case ReplyKind::Probe:
      hasProbe_ = true;
      probe_ = static_cast<ProbeState>(r.state);
      changes_++;
      break;
    case ReplyKind::Job: job(r); break;
    case ReplyKind::Fault:
      if (faultCount_ == kFaults) {
        memmove(faults_, faults_ + 1, sizeof faults_[0] * (kFaults - 1));
        faultCount_--;
      }
      faults_[faultCount_++] = {r.code, nowMs};
      changes_++;
      break;
    case ReplyKind::Start:  // a restarted Mega has no job running and must be asked again
      job_ = JobState::Idle;
      hasPosition_ = false;
      changes_++;
      break;
    default: break;
  }
}

void StatusFold::job(const Reply& r) {
  JobState before = job_;
  job_ = static_cast<JobState>(r.state);
  hasJob_ = true;
  const char* v = nullptr;
  int n = field(r.text, r.textLen, "file", &v);
  if (n >= 0) snprintf(jobFile_, sizeof jobFile_, "%.*s", n, v);
  n = field(r.text, r.textLen, "stop", &v);
  if (n > 0) {
    char t[24];
    snprintf(t, sizeof t, "%.*s", n, v);
    char* slash = nullptr;
    stop_ = static_cast<uint32_t>(strtoul(t, &slash, 10));
    stops_ = slash && *slash == '/' ? static_cast<uint32_t>(strtoul(slash + 1, nullptr, 10)) : 0;
  }
  if (job_ != before) changes_++;
}

void StatusFold::limit(const char* text, uint8_t len) {
  // The T: line carries no limits (a host would show them as targets): they are config.
  static const char kKey[] = "M850 thermal.limit.";
  const uint8_t k = sizeof kKey - 1;
  if (len < k + 3 || memcmp(text, kKey, k) != 0 || text[k] < '0' || text[k] >= '0' + kSensorCount || text[k + 1] != ' ') return;
  int32_t milli = 0;
  if (!parseMilli(text + k + 2, static_cast<uint8_t>(len - k - 2), milli)) return;
  uint8_t i = static_cast<uint8_t>(text[k] - '0');
  limitDeciC_[i] = static_cast<int16_t>(milli / 100);
  limitsKnown_ = static_cast<uint8_t>(limitsKnown_ | (1 << i));
  changes_++;
}

void StatusFold::write(JsonWriter& w, const UploadProgress* upload, uint8_t clients, uint32_t nowMs) const {
  w.beginObject();
  w.key("mega").string(online(nowMs) ? "online" : "offline");
  w.key("firmware");
  if (firmware_[0]) w.ascii(firmware_, static_cast<uint16_t>(strlen(firmware_)));
  else w.null();
  w.key("position");
  if (hasPosition_) {
    w.beginObject().key("x").fixed(um_[0], 3).key("y").fixed(um_[1], 3).key("z").fixed(um_[2], 3).endObject();
  } else {
    w.null();
  }
  w.key("temps");
  if (hasTemps_) {
    w.beginArray();
    for (int16_t t : deciC_) w.fixed(t, 1);
    w.endArray();
  } else {
    w.null();
  }
  w.key("limits");
  if (limitsKnown_ == (1 << kSensorCount) - 1) {
    w.beginArray();
    for (int16_t t : limitDeciC_) w.fixed(t, 1);
    w.endArray();
  } else {
    w.null();
  }
  w.key("job");
  if (hasJob_ || upload) {
    w.beginObject();
    w.key("state").string(jobStateName(job_));
    w.key("file");
    if (jobFile_[0]) w.ascii(jobFile_, static_cast<uint16_t>(strlen(jobFile_)));
    else w.null();
    w.key("stop").number(stop_).key("stops").number(stops_);
    if (upload) {
      w.key("id").number(upload->id);
      w.key("upload").string(upload->state == UploadState::Started ? "started" : upload->state == UploadState::Failed ? "failed" : "uploading");
      w.key("bytesSent").number(upload->bytesSent).key("bytesVerified").number(upload->bytesVerified).key("bytesTotal").number(upload->bytesTotal);
    } else {
      w.key("id").null();
    }
    w.endObject();
  } else {
    w.null();
  }
  w.key("probe");
  if (hasProbe_) w.string(kProbeNames[static_cast<uint8_t>(probe_)]);
  else w.null();
  w.key("faults").beginArray();
  for (uint8_t i = 0; i < faultCount_; i++) {
    if (nowMs - faults_[i].atMs >= kFaultMs) continue;
    char code[8];
    snprintf(code, sizeof code, "E%u", faults_[i].code);
    w.string(code);
  }
  w.endArray();
  w.key("clients").number(clients);
  w.endObject();
}

}  // namespace esp
}  // namespace uv
