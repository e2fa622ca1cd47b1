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
bool isEndOrStop(const LineSlot& l) {
  return l.len >= 3 && (l.text[0] == 'M' || l.text[0] == 'm') &&
         ((l.text[1] == '2' && l.text[2] == '9' && (l.len == 3 || l.text[3] == ' ')) || isEmergencyStop(l.text, l.len));
}

// A G or M and a digit: a command word, which no job record starts with.
bool isCommandLine(const LineSlot& l) {
  return l.len >= 2 && (l.text[0] == 'G' || l.text[0] == 'M' || l.text[0] == 'g' || l.text[0] == 'm') && l.text[1] >= '0' && l.text[1] <= '9';
}

// Obeyed between a stream's records, so a running stream can be watched, paused and aborted.
bool isStreamCommand(const LineSlot& l) {
  uv::Command c;
  if (uv::parseCommand(l.text, l.len, c) || c.letter != 'M') return false;
  switch (c.code) {
    case 24: case 25: case 524: case 27: case 105: case 114: case 115: case 154: case 155:
      return true;
    default:
      return false;
  }
}

// Queries that may run while another port's long command is under way.
bool isQuery(const uv::Command& c) {
  if (c.letter != 'M') return false;
  switch (c.code) {
    case 105: case 114: case 115: case 154: case 155: case 27:
      return true;
    default:
      return false;
  }
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
  for (uint8_t i = 0; i < kPorts; i++) {
    uint8_t k = static_cast<uint8_t>((next_ + i) % kPorts);
    HostLink& port = *ports_[k];
    const LineSlot* line = port.front();
    if (!line || port.room() < kReplyRoom) continue;
    if (long_.op != Op::None) {
      uv::Command c;
      if (long_.port == &port || uv::parseCommand(line->text, line->len, c) || !isQuery(c)) continue;
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
  if (halted_ && !c.is('M', 999) && !c.is('M', 112)) {
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

Machine::Result Machine::dispatch(HostLink& port, const uv::Command& c) {
  char buf[112];
  if (c.letter == 'G') {
    switch (c.code) {
      case 0: case 1: return move(port, c);
      case 4: return dwell(port, c);
      case 28: return home(c);
      case 29: return level(port, c);
      case 30: return probeOnce(port);
      case 90: absolute_ = true; return Result::Done;
      case 91: absolute_ = false; return Result::Done;
      default: break;
    }
  } else {
    switch (c.code) {
      case 115:
        long_.op = Op::Emit;
        long_.gen = Gen::Firmware;
        long_.index = 0;
        return Result::Long;
      case 110: port.errorLine(uv::kBadParameter); return Result::Done;  // the receiver takes every good M110
      case 105: return temperatures(port);
      case 155:
      case 154: {
        // S in seconds (both), or P in milliseconds (M154), at least 50 ms; 0 stops.
        int32_t ms = -1;
        if (c.code == 154 && c.hasValue('P')) ms = c.value('P') / 1000;
        else if (c.hasValue('S')) ms = c.value('S');  // thousandths of a second = ms
        if (ms < 0 || ms > 60000 || (ms > 0 && ms < 50)) {
          port.errorLine(uv::kBadParameter);
          return Result::Done;
        }
        uint32_t& period = c.code == 155 ? tempPeriodUs_ : posPeriodUs_;
        period = static_cast<uint32_t>(ms) * 1000;
        (c.code == 155 ? tempNext_ : posNext_) = now_ + period;
        return Result::Done;
      }
      case 114:
        formatPosition(buf);
        port.line(buf);
        return Result::Done;
      case 119:
        long_.op = Op::ProbeRead;
        head_.requestProbe();
        return Result::Long;
      case 17:
        io_.motorsEnabled(true);
        return Result::Done;
      case 18: case 84: return release();
      case 410:
        motion_.stop();
        return Result::Done;
      case 400: return drain();
      case 113: return busyInterval(port, c);
      case 108: return Result::Done;  // Marlin's "stop waiting for heaters": nothing here heats or waits for heat
      case 21:  // Marlin's "init card": the card is mounted at start; say whether it is there
        port.lineP(sd_.present() ? UV_P("echo:SD card ok") : UV_P("echo:SD init fail"));
        return Result::Done;
      case 820: return jog(port, c);
      case 822: return selfTest(port, c);
      case 401: return servo(port, c, 'D');
      case 402: return servo(port, c, 'U');
      case 280: return servo(port, c, 0);
      case 355: return light(port, c);
      case 117: return message(c);
      case 420: return meshCommand(port, c);
      case 821: return diagnostics(port, c);
      case 850: case 500: case 501: case 502: case 503: return configCommand(port, c);
      case 20: case 23: case 24: case 25: case 26: case 27: case 28: case 29: case 30: case 32: case 524: case 828: case 1000:
        return jobCommand(port, c);
      case 112: return Result::Done;  // acted on when it arrived
      case 999:
        halted_ = false;
        lastFault_ = 0;
        return Result::Done;
      default: break;
    }
  }
  char word[8];
  word[0] = c.letter;
  word[1 + uv::putUnsigned(c.code, word + 1)] = 0;
  port.errorLine(uv::kUnknownCommand, word);
  return Result::Done;
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
