// Job commands of the command core (protocol/mega.md "Jobs"): upload to SD with every record
// checked, planning into the stop file, select, start, pause, continue, abort, status and delete.
// A job while it runs, streams and resume are in machine_job_run.cpp.
#include <new>
#include <string.h>

#include "dialect_reply.h"
#include "error_codes.h"
#include "machine.h"
#include "progmem.h"
#include "text_scan.h"

namespace mega {

void Machine::clearArena() {
  switch (arena_) {  // each stage was placed in the arena as exactly its type
    case Arena::Spool: spool()->JobSpool::~JobSpool(); break;
    case Arena::Plan: plan()->JobPlan::~JobPlan(); break;
    case Arena::Run: run()->JobRunner::~JobRunner(); break;
    case Arena::Stream: stream()->StreamArena::~StreamArena(); break;
    case Arena::Gcode: gcode()->GcodeFile::~GcodeFile(); break;
    default: break;
  }
  arena_ = Arena::Empty;
  preparing_ = false;
  streaming_ = false;
}

uint8_t Machine::refuseExposure(HostLink& port, bool heatWaits) {
  if (!head_.online()) {
    port.errorLine(uv::kNanoTimeout);
    return uv::kNanoTimeout;
  }
  if (head_.activeFaults() & uv::fault::kSensor) {  // a broken sensor does not clear by cooling
    port.errorLine(uv::kSensorFault);
    return uv::kSensorFault;
  }
  if (!heatWaits && headHot(head_, config_)) {
    port.errorLineP(uv::kOverTemperature, UV_P("printhead faulted"));
    return uv::kOverTemperature;
  }
  if (!axisHomed(0) || !axisHomed(1)) {
    port.errorLineP(uv::kNotHomed, UV_P("home first (G28)"));
    return uv::kNotHomed;
  }
  return 0;
}

Machine::Result Machine::uploadRecord(HostLink& port, const LineSlot& line) {
  uint8_t before = spool()->error();
  uint8_t err = spool()->record(line.text, line.len);
  if (err && !before) {  // the first bad record says why; the rest are read and dropped
    char detail[16];
    uvMemcpyP(detail, UV_P("line "), 5);
    detail[5 + uv::putUnsigned(spool()->errorLine(), detail + 5)] = 0;
    port.errorLine(err, detail);
  }
  return Result::Done;
}

JobRunner* Machine::newRunner() {
  JobRunner* r = new (arenaMem_) JobRunner(sd_, motion_, head_, config_, leveling_ ? &mesh_ : nullptr);
  r->setScanMemory(arenaMem_ + kRunnerBytes, static_cast<uint16_t>(kArenaBytes - kRunnerBytes));
  arena_ = Arena::Run;
  return r;
}

uint8_t Machine::startPlanning(const uv::JobHeader& header) {
  // Plans start from the origin, at the link's speed now (kept in the stop file): the same plan whenever it runs.
  uv::MotionModel m = mega::plannerMachine(config_, 0, 0, head_.jobBaud());
  char name[kFileNameMax + 1];
  strcpy(name, selected_);
  clearArena();
  JobPlan* p = new (arenaMem_) JobPlan(sd_, header, m);
  arena_ = Arena::Plan;
  uint8_t err = p->begin(name);
  if (err) {
    clearArena();
    removeWorkFiles(sd_, name);  // nothing half-built stays; the job's text does
  }
  return err;
}

void Machine::planRefused(HostLink& port, uint8_t err) {
  selected_[0] = 0;
  jobState_ = uv::JobState::Failed;
  if (err == uv::kJobMalformed) port.errorLineP(err, UV_P("the LEDs' rows span 1024 rows or more"));
  else port.errorLine(err);
}

Machine::Result Machine::endUpload(HostLink& port) {
  uint8_t err = spool()->finish();
  if (err) {
    clearArena();
    jobState_ = uv::JobState::Failed;
    port.errorLine(err);
    return Result::Done;
  }
  uv::JobHeader header = spool()->header();
  strcpy(selected_, spool()->name());
  err = startPlanning(header);
  if (err) {
    planRefused(port, err);
    return Result::Done;
  }
  long_.op = Op::Plan;
  return Result::Long;
}

bool Machine::refuseCardJob(HostLink& port) {
  if (!sd_.present()) {
    port.errorLine(uv::kNoSd);
    return true;
  }
  if (jobActive()) {
    port.errorLine(uv::kBusy);
    return true;
  }
  return false;
}

Machine::Result Machine::select(HostLink& port, const uv::Command& c) {
  if (refuseCardJob(port)) return Result::Done;
  char name[kFileNameMax + 1];
  memcpy(name, c.text, c.textLen);
  name[c.textLen] = 0;
  FileHandle f = sd_.open(name, Storage::Mode::Read);
  if (f < 0 || isWorkFile(name)) {
    if (f >= 0) sd_.close(f);
    port.errorLine(uv::kFileNotFound, name);
    return Result::Done;
  }
  saySelected(port, name, c.textLen, sd_.size(f));
  clearArena();
  strcpy(selected_, name);
  jobState_ = uv::JobState::Idle;
  // A job copied onto the card by a PC has no working files yet: verify it and plan it now.
  char work[kWorkNameMax + 1];
  workFileName(name, JobFile::Stops, work);
  FileHandle stops = sd_.open(work, Storage::Mode::Read);
  StopFileHeader h;
  bool planned = stops >= 0 && readStopHeader(sd_, stops, h);
  if (stops >= 0) sd_.close(stops);
  if (planned) {
    sd_.close(f);
    jobState_ = uv::JobState::Ready;
    return Result::Done;
  }
  sd_.close(f);
  JobSpool* s = new (arenaMem_) JobSpool(sd_);
  arena_ = Arena::Spool;
  preparing_ = true;
  uint8_t err = s->beginPrepared(name);
  if (err) {
    s->abandon();
    clearArena();
    port.errorLine(err, name);
    return Result::Done;
  }
  long_.op = Op::Prepare;
  return Result::Long;
}

Machine::Result Machine::startOrContinue(HostLink& port, const uv::Command& c) {
  Pace pace = paceParam(port, c);
  if (pace == Pace::Bad) return Result::Done;
  if (running() && run()->state() == RunState::Paused) {
    // A continue that runs the job paced (P1, or no P for a paced job) waits out heat rather than
    // being refused for it: first the wait to cool, then the job (mega.md "Pacing").
    const bool paced = pace == Pace::On || (pace == Pace::Unsaid && run()->paced());
    if (refuseExposure(port, paced)) return Result::Done;
    run()->setPaced(paced);
    run()->resume(now_, paced && headHot(head_, config_));
    return Result::Done;
  }
  if (running() && run()->state() == RunState::Running) {
    port.errorLine(uv::kBusy);
    return Result::Done;
  }
  if (!selected_[0] || arena_ == Arena::Spool || arena_ == Arena::Plan || jobState_ == uv::JobState::Idle) {
    port.errorLine(uv::kNoJob);
    return Result::Done;
  }
  if (refuseExposure(port)) return Result::Done;
  clearArena();
  JobRunner* r = newRunner();
  r->setPaced(pace == Pace::On);
  uint8_t err = r->start(selected_, 0, now_);
  if (err) {
    clearArena();
    port.errorLine(err, selected_);
  }
  return Result::Done;
}

Machine::Result Machine::jobCommand(HostLink& port, const uv::Command& c) {
  char name[kFileNameMax + 1];
  Result handled;
  if (gcodeCommand(port, c, handled)) return handled;
  switch (c.code) {
    case 20:
      if (arena_ == Arena::Stream && jobActive()) {
        port.errorLine(uv::kBusy);
        return Result::Done;
      }
      if (!sd_.present()) {
        port.errorLine(uv::kNoSd);
        return Result::Done;
      }
      long_.op = Op::Emit;
      long_.gen = Gen::Files;
      long_.index = 0;
      long_.fileIndex = 0;
      return Result::Long;
    case 28: {
      if (refuseCardJob(port)) return Result::Done;
      memcpy(name, c.text, c.textLen);
      name[c.textLen] = 0;
      clearArena();
      selected_[0] = 0;
      JobSpool* s = new (arenaMem_) JobSpool(sd_);
      arena_ = Arena::Spool;
      jobPort_ = &port;
      if (s->begin(name)) {
        clearArena();
        port.errorLine(uv::kFileError, name);
        return Result::Done;
      }
      char buf[56];
      uvMemcpyP(buf, UV_P("echo:Writing to file: "), 22);
      strcpy(buf + 22, name);
      port.line(buf);
      return Result::Done;
    }
    case 828: return startStream(port, c);
    case 29:
      if (((arena_ == Arena::Spool && !preparing_) || (arena_ == Arena::Stream && streaming_)) && &port != jobPort_) {
        port.errorLine(uv::kBusy);  // the other port's upload or stream is not this one's to end
        return Result::Done;
      }
      if (arena_ == Arena::Stream && streaming_) {
        streaming_ = false;
        uint8_t err = stream()->job.finish();
        if (err) {
          stream()->runner.abort();
          port.errorLine(err);
        } else {
          port.lineP(UV_P("echo:Stream complete."));
        }
        return Result::Done;
      }
      if (arena_ != Arena::Spool || preparing_) {
        port.errorLineP(uv::kBadParameter, UV_P("not uploading"));
        return Result::Done;
      }
      return endUpload(port);
    case 23: return select(port, c);
    case 24: return startOrContinue(port, c);
    case 25:
      if (running()) run()->pause(0);
      return Result::Done;
    case 524:
      if (running()) run()->abort();
      else if (arena_ == Arena::Spool) {
        spool()->abandon();
        clearArena();
        jobState_ = uv::JobState::Aborted;
      }
      head_.allOff();
      motion_.stop();
      return Result::Done;
    case 27: {
      if (c.has('S')) {
        int32_t ms = c.hasValue('S') ? c.value('S') : -1;
        if (ms < 0 || ms > 60000) {
          port.errorLine(uv::kBadParameter);
          return Result::Done;
        }
        jobPeriodUs_ = static_cast<uint32_t>(ms) * 1000;
        jobNext_ = now_ + jobPeriodUs_;
        return Result::Done;
      }
      char buf[kJobLineMax];
      formatJob(buf);
      port.line(buf);
      return Result::Done;
    }
    case 30:
      memcpy(name, c.text, c.textLen);
      name[c.textLen] = 0;
      if (!sd_.present() || !sd_.exists(name) || isWorkFile(name)) {
        port.errorLine(uv::kFileNotFound, name);
        return Result::Done;
      }
      if (jobActive() && (strcmp(name, selected_) == 0 || arena_ == Arena::Stream)) {
        port.errorLine(uv::kBusy);
        return Result::Done;
      }
      removeJob(sd_, name);
      if (strcmp(name, selected_) == 0) selected_[0] = 0;
      return Result::Done;
    case 1000: return resumeInterrupted(port, c);
    default:
      return Result::Done;
  }
}

// Marlin's two lines after M23, which OctoPrint waits for: the same for job files and G-code files.
void Machine::saySelected(HostLink& port, const char* name, uint8_t len, uint32_t size) {
  char buf[64];
  char* p = buf;
  p += uv::putFlash(UV_P("File opened: "), p);
  memcpy(p, name, len);
  p += len;
  p += uv::putFlash(UV_P(" Size: "), p);
  p[uv::putUnsigned(size, p)] = 0;
  port.line(buf);
  port.lineP(UV_P("File selected"));
}

}  // namespace mega
