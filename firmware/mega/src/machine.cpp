// The Mega's command core: lines from both ports in turn, long commands as state machines, reports.
#include "machine.h"
#include "machine_budget.h"
#include "progmem.h"

#include <string.h>

#include "dialect_reply.h"
#include "error_codes.h"
#include "job_files.h"
#include "text_scan.h"

namespace mega {

namespace {
// Obeyed between a stream's records, so a running stream can be watched, paused and aborted.
bool isStreamCommand(const LineSlot& l) {
  uv::Command c;
  return !uv::parseCommand(l.text, l.len, c) && (Machine::commandFlags(c) & Machine::kStream);
}
bool isEndOrStop(const LineSlot& l) {
  return l.len >= 3 && (l.text[0] == 'M' || l.text[0] == 'm') &&
         ((l.text[1] == '2' && l.text[2] == '9' && (l.len == 3 || l.text[3] == ' ')) || isEmergencyStop(l.text, l.len));
}

// A G or M and a digit: a command word, which no job record starts with.
bool isCommandLine(const LineSlot& l) {
  return l.len >= 2 && (l.text[0] == 'G' || l.text[0] == 'M' || l.text[0] == 'g' || l.text[0] == 'm') && l.text[1] >= '0' && l.text[1] <= '9';
}

}  // namespace

Machine::Machine(const MachineParts& p)
    : motion_(p.motion), head_(p.head), config_(p.config), store_(p.store), sd_(p.sd), io_(p.io),
      homing_(p.motion, p.config), test_(p.motion, p.config), probe_(p.motion, p.head), mesh_(p.eeprom), screen_(p.display), firmwareName_(p.firmwareName), movesFree_(p.movesFree), stats_(p.stats) {
  for (uint8_t i = 0; i < kPorts; i++) ports_[i] = p.ports[i];
}

void Machine::begin(uint32_t nowUs) {
  now_ = nowUs;
  store_.load();
  mesh_.load();  // kept, but not applied until M420 S1 or G29
  head_.begin(nowUs);
  applyConfig();
  posNext_ = nowUs + posPeriodUs_;
  for (HostLink* p : ports_) p->lineP(UV_P("start"));
}

void Machine::broadcast(const char* text) {
  for (HostLink* p : ports_) p->report(text);
}

void Machine::broadcastP(const char* text) {
  for (HostLink* p : ports_) p->reportP(text);
}

void Machine::emergency() {
  head_.allOff();
  motion_.halt();
  homing_.cancel();
  probe_.cancel();
  if (running()) run()->abort();
  if (arena_ == Arena::Spool) spool()->abandon();
  streaming_ = false;  // M112 ends a stream at once
  if (arena_ != Arena::Run) clearArena();
  io_.motorsEnabled(false);
  homed_ = 0;  // steps may have been lost: home again after M999
  feedUmS_ = 0;  // Marlin's M112 ends in a reset, which forgets the F: the configured speed again
  halted_ = true;
  if (long_.op != Op::None) finishLong(uv::kHalted);
}

void Machine::poll(uint32_t nowUs) {
  now_ = nowUs;
  for (HostLink* p : ports_)
    if (p->poll()) emergency();
  head_.poll(nowUs, {&Machine::doseRecord, this});
  printheadEvents();
  motion_.poll();
  movesFree_ = motion_.movesFree();
  store_.poll();
  mesh_.poll();
  if (long_.op != Op::None) runLong();
  runJob();
  // Lines run in turn from each port. While a long command runs, the other port's queries still run.
  bool ran = false;
  // A dose record to ask for, or on its way, goes before the hosts' lines: it needs the room their
  // replies would take, and the Nano keeps only two (protocol/mega.md "Dose reports").
  const bool doseFirst = !head_.doseDrained();
  for (uint8_t i = 0; i < kPorts; i++) {
    uint8_t k = static_cast<uint8_t>((next_ + i) % kPorts);
    HostLink& port = *ports_[k];
    const LineSlot* line = port.front();
    if (!line || port.room() < kReplyRoom || doseFirst) continue;
    if (long_.op != Op::None) {
      uv::Command c;
      if (long_.port == &port || uv::parseCommand(line->text, line->len, c) || !(commandFlags(c) & kQuery)) continue;
    }
    Result r = execute(port, *line);
    if (r == Result::Wait) continue;
    if (r == Result::Done) port.ok();
    next_ = static_cast<uint8_t>((k + 1) % kPorts);
    ran = true;
    break;
  }
  if (!ran) runCardLine();  // a G-code file's lines run between the hosts' lines
  reports();
  jobReports();
  panel();
}

Machine::Result Machine::execute(HostLink& port, const LineSlot& line) {
  // An upload's or a stream's records come from the port that began it; the other port's lines run
  // as usual. A plain line there is not a record: on a noisy wire it is most likely the tail of a
  // numbered line that a damaged byte split, and every host numbers its records (mega.md §5).
  bool jobPort = &port == jobPort_;
  // A G-code upload stores every line of its port but M29 (and M112, acted on as it arrived).
  if (arena_ == Arena::Gcode && gcode()->uploading() && jobPort && !isEndOrStop(line)) return storeGcodeLine(port, line);
  if (jobPort && line.n < 0 && !isCommandLine(line) &&
      ((arena_ == Arena::Spool && !preparing_) || (arena_ == Arena::Stream && streaming_))) {
    port.errorLineP(uv::kNoLineNumber, UV_P("a job record needs a line number"));
    return Result::Done;
  }
  // During an upload, its port's commands run too: records never start with a G or M and a digit.
  if (arena_ == Arena::Spool && !preparing_ && jobPort && !isCommandLine(line)) return uploadRecord(port, line);
  if (arena_ == Arena::Stream && streaming_ && jobPort && !isEndOrStop(line) && !isStreamCommand(line)) {
    // Once the stream's job has ended, a command shows its host has moved on: the stream is over
    // and the line is obeyed.
    if (isCommandLine(line) && !runLive()) streaming_ = false;
    else return streamLine(port, line);
  }
  uv::Command c;
  uint8_t err = uv::parseCommand(line.text, line.len, c);
  if (err) {
    char word[8] = {};
    if (err == uv::kUnknownCommand) {
      uint8_t n = 0;
      while (n < line.len && n < sizeof word - 1 && line.text[n] != ' ') {
        word[n] = line.text[n];
        n++;
      }
    }
    port.errorLine(err, word[0] ? word : nullptr);
    return Result::Done;
  }
  if (halted_ && !(commandFlags(c) & kWhileHalted)) {
    port.errorLine(uv::kHalted);
    return Result::Done;
  }
  Result r = dispatch(port, c);
  if (r == Result::Long) {
    long_.port = &port;
    long_.fromCard = false;
    long_.since = now_;
    long_.keepalive = now_ + kKeepaliveUs;
  }
  return r;
}

uint32_t Machine::keepaliveUs(const HostLink* port) const {
  for (uint8_t i = 0; i < kPorts; i++)
    if (ports_[i] == port) return static_cast<uint32_t>(keepaliveS_[i]) * 1000000;
  return kKeepaliveUs;  // the panel's commands have no port
}

void Machine::finishLong(uint8_t error, const char* detail) {
  HostLink* port = long_.port;
  if (port && port->room() < kReplyRoom) {
    // Its reply block must go out whole (an M112 from the other port can end a command while this
    // port's ring is full): it waits, as Answer, with what it will say.
    if (long_.op == Op::Answer) return;  // already waiting: the first verdict stands
    long_.op = Op::Answer;
    long_.error = error;
    long_.detail[0] = 0;
    if (detail) {
      strncpy(long_.detail, detail, sizeof long_.detail - 1);
      long_.detail[sizeof long_.detail - 1] = 0;
    }
    return;
  }
  long_.op = Op::None;
  if (!port) {  // started from the panel: an error is everyone's news, and there is no ok
    if (error) {
      for (HostLink* p : ports_) p->errorLine(error, detail);
      lastFault_ = error;
    }
    return;
  }
  if (error) port->errorLine(error, detail);
  if (!long_.fromCard) port->ok();
  else if (error && uv::isFault(error)) stopCardFile();
}

}  // namespace mega
