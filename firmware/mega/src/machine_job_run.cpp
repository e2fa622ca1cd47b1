// A job on the card or a stream while it runs (protocol/mega.md "Jobs", "Stream mode", "Resume"): its
// JOB: line, the pause when every host has gone quiet, resume from the checkpoint, and stream mode's records.
#include <new>
#include <string.h>

#include "dialect_reply.h"
#include "error_codes.h"
#include "machine.h"
#include "nano_codec.h"
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

// Times in a JOB: line stop at 9999999 s (115 days), which keeps the longest line whole (kJobLineMax).
uint32_t capS(uint32_t s) { return s > 9999999 ? 9999999 : s; }
}  // namespace

uint8_t Machine::formatJob(char* out) const {
  uv::Reply r{};
  r.kind = uv::ReplyKind::Job;
  char fields[kJobLineMax - 11];  // the fields after `JOB:<state>`; see kJobLineMax
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
    p += uv::putUnsigned(capS(j.elapsedS(now_)), p);
    if (j.planComplete()) {  // a stream's end, and so its time left, is not known until its last row
      p += uv::putFlash(UV_P(" remaining="), p);
      p += uv::putUnsigned(capS(j.remainingS()), p);
    }
    p += uv::putFlash(UV_P(" leds="), p);
    p += uv::putUnsigned(head_.fireState() == FireState::Firing ? 1 : 0, p);
    if (j.state() == RunState::Paused) {
      p += uv::putFlash(UV_P(" reason="), p);
      p += uv::putFlash(reasonName(j.reason()), p);
    }
    if (j.streaming()) p += uv::putFlash(UV_P(" mode=stream"), p);
    if (j.paced()) p += uv::putFlash(UV_P(" paced=1"), p);
    if (j.cooling()) p += uv::putFlash(UV_P(" cooling=1"), p);
  } else {
    r.state = static_cast<uint8_t>(arena_ == Arena::Spool ? uv::JobState::Uploading : jobState_);
  }
  r.text = fields;
  r.textLen = static_cast<uint8_t>(p - fields);
  return static_cast<uint8_t>(uv::formatReply(r, out, kJobLineMax));
}


Pace Machine::paceParam(HostLink& port, const uv::Command& c) {
  Pace pace = paceOf(c);
  if (pace == Pace::Bad) port.errorLineP(uv::kBadParameter, UV_P("P is 0 or 1"));
  return pace;
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
  Pace pace = paceParam(port, c);
  if (pace == Pace::Bad) return Result::Done;
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
  JobRunner* r = newRunner();
  r->setPaced(pace == Pace::On);
  uint8_t err = r->resume(p, now_);
  if (err) {
    clearArena();
    port.errorLine(err, p.file);
  }
  return Result::Done;
}

Machine::Result Machine::startStream(HostLink& port, const uv::Command& c) {
  Pace pace = paceParam(port, c);
  if (pace == Pace::Bad) return Result::Done;
  if (jobActive()) {
    port.errorLine(uv::kBusy);
    return Result::Done;
  }
  if (refuseExposure(port)) return Result::Done;
  clearArena();
  int32_t here[3];
  motion_.targetUm(here);
  uv::MotionModel m = mega::plannerMachine(config_, here[0], here[1], head_.jobBaud());  // the stream runs at this speed
  // The buffer is the card's sector cache (or its stand-in): no card command runs until the stream ends.
  StreamArena* a = reinterpret_cast<StreamArena*>(arenaMem_);
  new (&a->job) StreamJob(sd_.scratch(), kScratchBytes, m);
  new (&a->runner) JobRunner(sd_, motion_, head_, config_, leveling_ ? &mesh_ : nullptr);
  arena_ = Arena::Stream;
  jobPort_ = &port;
  streaming_ = true;
  streamWaiting_ = false;
  port.lineP(UV_P("echo:Streaming: exposed as it arrives, no resume"));
  a->runner.setPaced(pace == Pace::On);
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
  // A fault that paused the job, or ended a stream (which cannot pause: its rows are gone).
  const bool stopped = j.state() == RunState::Paused || j.state() == RunState::Failed;
  if (stopped && before == RunState::Running && j.reason() && j.reason() != kReasonLostHost) {
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
    uint8_t hot = j.reason() == uv::kOverTemperature ? j.tooHot() : 0;
    if (hot) {  // a soft limit: which sensor, at what reading (mega.md "Pacing")
      *p++ = ' ';
      *p++ = 'T';
      *p++ = static_cast<char>('0' + hot - 1);
      *p++ = ' ';
      p += uv::formatDeciC(head_.deciC()[hot - 1], p);
      uvMemcpyP(p, UV_P(" (soft limit)"), 14);
    } else {
      uvMemcpyP(p, UV_P(" at stop "), 9);
      p += 9;
      p[uv::putUnsigned(j.faultStop(), p)] = 0;
    }
    if (!broadcastWhole(buf)) return;
    faultToShow_ = false;
  }
  if (j.changed()) {  // every change of state goes to both hosts, whole
    char buf[kJobLineMax];
    formatJob(buf);
    if (broadcastWhole(buf)) j.clearChanged();
  }
}

void Machine::jobReports() {
  if (!jobPeriodUs_ || static_cast<int32_t>(now_ - jobNext_) < 0) return;
  jobNext_ = now_ + jobPeriodUs_;
  char buf[kJobLineMax];
  if (!formatCardProgress(buf)) formatJob(buf);  // M27 S reports what M27 answers
  broadcast(buf);
}


}  // namespace mega
