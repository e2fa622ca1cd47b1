// Job commands of the command core (protocol/mega.md "Jobs"): upload to SD with every record
// checked, planning into the stop file, select, start, pause, continue, abort, status, delete,
// and resume after an interruption from the checkpoint.
#include <new>
#include <string.h>

#include "dialect_reply.h"
#include "error_codes.h"
#include "machine.h"
#include "progmem.h"
#include "text_scan.h"

namespace mega {

namespace {
constexpr uint32_t kLostHostUs = 30000000;  // no line from any host for 30 s while running: pause

// Why a job paused, for its JOB: line (a string in flash).
const char* reasonName(uint8_t code) {
  switch (code) {
    case 0: return UV_P("user");
    case 30: return UV_P("printhead");
    case 31: return UV_P("overtemp");
    case 33: return UV_P("refused");
    case 20: case 21: case 22: return UV_P("sd");
    case 99: return UV_P("host");
    default: return UV_P("fault");
  }
}
constexpr uint8_t kReasonLostHost = 99;
}  // namespace

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

uint8_t Machine::formatJob(char* out) const {
  uv::Reply r{};
  r.kind = uv::ReplyKind::Job;
  char fields[80];
  char* p = fields;
  if (running()) {
    const JobRunner& j = *run();
    static const uv::JobState kStates[] = {uv::JobState::Running, uv::JobState::Paused, uv::JobState::Done, uv::JobState::Aborted, uv::JobState::Failed};
    r.state = static_cast<uint8_t>(kStates[static_cast<uint8_t>(j.state())]);
    p += uv::putFlash(UV_P(" file="), p);
    size_t n = strlen(j.file());
    memcpy(p, j.file(), n);
    p += n;
    p += uv::putFlash(UV_P(" stop="), p);
    p += uv::putUnsigned(j.done(), p);
    *p++ = '/';
    p += uv::putUnsigned(j.count(), p);
    p += uv::putFlash(UV_P(" elapsed="), p);
    p += uv::putUnsigned(j.elapsedS(now_), p);
    if (j.planComplete()) {  // a stream's end, and so its time left, is not known until its last row
      p += uv::putFlash(UV_P(" remaining="), p);
      p += uv::putUnsigned(j.remainingS(), p);
    }
    p += uv::putFlash(UV_P(" leds="), p);
    p += uv::putUnsigned(head_.fireState() == FireState::Firing ? 1 : 0, p);
    if (j.state() == RunState::Paused) {
      p += uv::putFlash(UV_P(" reason="), p);
      p += uv::putFlash(reasonName(j.reason()), p);
    }
    if (j.streaming()) p += uv::putFlash(UV_P(" mode=stream"), p);
  } else {
    r.state = static_cast<uint8_t>(arena_ == Arena::Spool ? uv::JobState::Uploading : jobState_);
  }
  r.text = fields;
  r.textLen = static_cast<uint8_t>(p - fields);
  return static_cast<uint8_t>(uv::formatReply(r, out, 112));
}

uint8_t Machine::refuseExposure(HostLink& port) {
  if (!head_.online()) {
    port.errorLine(uv::kNanoTimeout);
    return uv::kNanoTimeout;
  }
  const int16_t* t = head_.deciC();
  bool hot = head_.activeFaults() != 0;
  for (uint8_t i = 0; i < uv::kSensorCount; i++) hot |= t[i] * 100 >= config_.milli(Key::ThermalLimit0 + i);
  if (hot) {
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

uv::Machine Machine::plannerMachine(int32_t x, int32_t y) const {
  uv::Machine m{};
  m.vmaxUmS[0] = m.vmaxUmS[1] = static_cast<uint32_t>(config_.milli(Key::SpeedTravel));
  m.accelUmS2[0] = static_cast<uint32_t>(config_.milli(Key::AccelX));
  m.accelUmS2[1] = static_cast<uint32_t>(config_.milli(Key::AccelY));
  m.settleUs = static_cast<uint32_t>(config_.whole(Key::SettleMs)) * 1000;
  m.overheadUs = static_cast<uint32_t>(config_.whole(Key::StopOverheadUs));
  m.startUm[0] = x;
  m.startUm[1] = y;
  return m;
}

uint8_t Machine::startPlanning(const uv::JobHeader& header) {
  uv::Machine m = plannerMachine(0, 0);  // plans start from the origin: the same plan whenever it runs
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
  char buf[64];
  char* p = buf;
  uvMemcpyP(p, UV_P("File opened: "), 13);
  p += 13;
  memcpy(p, name, c.textLen);
  p += c.textLen;
  uvMemcpyP(p, UV_P(" Size: "), 7);
  p += 7;
  p[uv::putUnsigned(sd_.size(f), p)] = 0;
  port.line(buf);
  port.lineP(UV_P("File selected"));
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

Machine::Result Machine::startOrContinue(HostLink& port) {
  if (running() && run()->state() == RunState::Paused) {
    if (refuseExposure(port)) return Result::Done;
    run()->resume(now_);
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
  JobRunner* r = new (arenaMem_) JobRunner(sd_, motion_, head_, config_, leveling_ ? &mesh_ : nullptr);
  arena_ = Arena::Run;
  uint8_t err = r->start(selected_, 0, now_);
  if (err) {
    clearArena();
    port.errorLine(err, selected_);
  }
  return Result::Done;
}

Machine::Result Machine::resumeInterrupted(HostLink& port, const uv::Command& c) {
  Progress p;
  bool have = sd_.present() && Checkpoint::read(sd_, p);
  if (c.has('S')) {
    char buf[96];
    if (!have || (running() && run()->state() == RunState::Running)) {
      port.lineP(UV_P("JOB:idle"));
      return Result::Done;
    }
    char* q = buf;
    uvMemcpyP(q, UV_P("JOB:interrupted file="), 21);
    q += 21;
    size_t n = strlen(p.file);
    memcpy(q, p.file, n);
    q += n;
    uvMemcpyP(q, UV_P(" stop="), 6);
    q += 6;
    q += uv::putUnsigned(p.done, q);
    *q++ = '/';
    q[uv::putUnsigned(p.count, q)] = 0;
    port.line(buf);
    return Result::Done;
  }
  if (jobActive()) {
    port.errorLine(uv::kBusy);
    return Result::Done;
  }
  if (c.has('C')) {
    Checkpoint(sd_).clear();
    return Result::Done;
  }
  if (!have) {
    port.errorLine(uv::kNoResume);
    return Result::Done;
  }
  if (refuseExposure(port)) return Result::Done;
  clearArena();
  strcpy(selected_, p.file);
  JobRunner* r = new (arenaMem_) JobRunner(sd_, motion_, head_, config_, leveling_ ? &mesh_ : nullptr);
  arena_ = Arena::Run;
  uint8_t err = r->resume(p, now_);
  if (err) {
    clearArena();
    port.errorLine(err, p.file);
  }
  return Result::Done;
}

Machine::Result Machine::startStream(HostLink& port) {
  if (jobActive()) {
    port.errorLine(uv::kBusy);
    return Result::Done;
  }
  if (refuseExposure(port)) return Result::Done;
  clearArena();
  int32_t here[3];
  motion_.targetUm(here);
  uv::Machine m = plannerMachine(here[0], here[1]);
  // The buffer is the card's sector cache (or its stand-in): no card command runs until the stream ends.
  StreamArena* a = reinterpret_cast<StreamArena*>(arenaMem_);
  new (&a->job) StreamJob(sd_.scratch(), kScratchBytes, m);
  new (&a->runner) JobRunner(sd_, motion_, head_, config_, leveling_ ? &mesh_ : nullptr);
  arena_ = Arena::Stream;
  jobPort_ = &port;
  streaming_ = true;
  streamWaiting_ = false;
  port.lineP(UV_P("echo:Streaming: exposed as it arrives, no resume"));
  a->runner.startStream(a->job, a->job.header(), now_);
  return Result::Done;
}

Machine::Result Machine::streamLine(HostLink& port, const LineSlot& line) {
  StreamArena& a = *stream();
  uint8_t before = a.job.error();
  if (before || !runLive()) return Result::Done;  // after a failure or an abort the rest is only read
  uint8_t r = a.job.record(line.text, line.len);
  if (r == kRecordWaits) {
    // No room until exposure frees some: the line waits, the host's window fills and it holds
    // back. A busy: at once tells it this is no lost line, then one every 2 s.
    if (!streamWaiting_ || static_cast<int32_t>(now_ - streamBusyAt_) >= 0) {
      port.reportP(UV_P("busy: processing"));
      streamBusyAt_ = now_ + kKeepaliveUs;
    }
    streamWaiting_ = true;
    return Result::Wait;
  }
  streamWaiting_ = false;
  if (r) {
    char detail[16];
    uvMemcpyP(detail, UV_P("line "), 5);
    detail[5 + uv::putUnsigned(a.job.errorLine(), detail + 5)] = 0;
    port.errorLine(r, r == uv::kStreamOverflow ? nullptr : detail);
    a.runner.abort();  // the LEDs off; what was exposed stays exposed
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
    case 828: return startStream(port);
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
    case 24: return startOrContinue(port);
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
      char buf[112];
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

void Machine::resumeVerdict(JobRunner& j) {
  JobRunner::Resumed v = j.resumedVerdict();
  if (v == JobRunner::Resumed::NotYet) return;
  char buf[112];
  char* p = buf;
  p += uv::putFlash(UV_P("echo:resume: stop "), p);
  p += uv::putUnsigned(j.resumedStop(), p);
  switch (v) {
    case JobRunner::Resumed::NotSent: p += uv::putFlash(UV_P(" had not been sent"), p); break;
    case JobRunner::Resumed::Exposed: p += uv::putFlash(UV_P(" had been exposed whole, and counts as done"), p); break;
    case JobRunner::Resumed::CutShort: p += uv::putFlash(UV_P(" was cut short, and is exposed again"), p); break;
    default: p += uv::putFlash(UV_P(" may have been cut short by the printhead's restart, and is exposed again"), p); break;
  }
  *p = 0;
  if (broadcastWhole(buf)) j.clearResumed();  // else again next pass: this one must not be lost
}

bool Machine::broadcastWhole(const char* text) {
  size_t n = strlen(text) + 1;
  for (HostLink* p : ports_)
    if (p->room() < n) return false;
  for (HostLink* p : ports_) p->line(text);
  return true;
}

void Machine::runJob() {
  if (!running()) return;
  JobRunner& j = *run();
  RunState before = j.state();
  j.poll(now_);
  resumeVerdict(j);
  if (j.state() == RunState::Running) {
    bool heard = false;
    for (HostLink* p : ports_) heard |= p->takeHeard();
    if (heard) lastHeardUs_ = now_;
    else if (now_ - lastHeardUs_ > kLostHostUs) j.pause(kReasonLostHost);
  } else {
    lastHeardUs_ = now_;
  }
  if (j.state() == RunState::Paused && before == RunState::Running && j.reason() && j.reason() != kReasonLostHost) {
    lastFault_ = j.reason();
    faultToShow_ = true;
  }
  if (faultToShow_) {  // the FAULT line first, whole, however long the hosts' rings take to empty
    char buf[80];
    char* p = buf;
    uvMemcpyP(p, UV_P("FAULT:E"), 7);
    p += 7;
    p += uv::putUnsigned(j.reason(), p);
    *p++ = ' ';
    uv::errorMessage(j.reason(), p, 48);
    p += strlen(p);
    uvMemcpyP(p, UV_P(" at stop "), 9);
    p += 9;
    p[uv::putUnsigned(j.faultStop(), p)] = 0;
    if (!broadcastWhole(buf)) return;
    faultToShow_ = false;
  }
  if (j.changed()) {  // every change of state goes to both hosts, whole
    char buf[112];
    formatJob(buf);
    if (broadcastWhole(buf)) j.clearChanged();
  }
}

void Machine::jobReports() {
  if (!jobPeriodUs_ || static_cast<int32_t>(now_ - jobNext_) < 0) return;
  jobNext_ = now_ + jobPeriodUs_;
  char buf[112];
  formatJob(buf);
  broadcast(buf);
}

}  // namespace mega
