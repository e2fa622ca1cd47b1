// The Mega's command core: lines from both ports in turn, long commands as state machines, reports.
#include "machine.h"
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

void strcpy_flash(char* out, const char* flash) { uvMemcpyP(out, flash, uvStrlenP(flash) + 1); }

// Room a command needs in its port's transmit ring before it runs: one payload line and the ok.
constexpr uint16_t kReplyRoom = 140;  // the longest payload line (112) and its ok
constexpr uint16_t kPlanStopsPerPass = 8;    // a few ms of card reads a main-loop pass
constexpr uint8_t kPrepareLinesPerPass = 4;

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
  halted_ = true;
  if (long_.op != Op::None) finishLong(uv::kHalted);
}

void Machine::poll(uint32_t nowUs) {
  now_ = nowUs;
  for (HostLink* p : ports_)
    if (p->poll()) emergency();
  head_.poll(nowUs);
  printheadEvents();
  motion_.poll();
  movesFree_ = motion_.movesFree();
  store_.poll();
  mesh_.poll();
  if (long_.op != Op::None) runLong();
  runJob();
  // Lines run in turn from each port. While a long command runs, the other port's queries still run.
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
    break;
  }
  reports();
  jobReports();
  panel();
}

Machine::Result Machine::execute(HostLink& port, const LineSlot& line) {
  // An upload's or a stream's records come from the port that began it; the other port's lines run
  // as usual. A plain line there is not a record: on a noisy wire it is most likely the tail of a
  // numbered line that a damaged byte split, and every host numbers its records (mega.md §5).
  bool jobPort = &port == jobPort_;
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
    long_.since = now_;
    long_.keepalive = now_ + kKeepaliveUs;
  }
  return r;
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
      case 20: case 23: case 24: case 25: case 27: case 28: case 29: case 30: case 524: case 828: case 1000:
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
  port->ok();
}

bool Machine::emitNext() {
  HostLink& port = *long_.port;
  char buf[112];
  uv::Reply r{};
  switch (long_.gen) {
    case Gen::Firmware: {
      static const char kWin[] UV_FLASH = "RX_WINDOW", kTemp[] UV_FLASH = "AUTOREPORT_TEMP", kPos[] UV_FLASH = "AUTOREPORT_POS",
                        kSd[] UV_FLASH = "SDCARD", kResume[] UV_FLASH = "RESUME";
      static const char* const kCaps[] UV_FLASH = {kWin, kTemp, kPos, kSd, kResume};
      char cap[32];
      if (long_.index == 0) {
        r.kind = uv::ReplyKind::Firmware;
        strcpy_flash(cap, firmwareName_);  // the name is in flash
        r.text = cap;
        r.textLen = static_cast<uint8_t>(strlen(cap));
        r.value = 1;
      } else if (long_.index <= 5) {
        uint8_t i = static_cast<uint8_t>(long_.index - 1);
        const uint32_t values[] = {kWindow, 1, 1, sd_.present() ? 1u : 0u, sd_.present() ? 1u : 0u};
        r.kind = uv::ReplyKind::Cap;
        strcpy_flash(cap, uvFlashPtr(kCaps[i]));
        r.text = cap;
        r.textLen = static_cast<uint8_t>(strlen(cap));
        r.value = values[i];
      } else {
        return false;
      }
      uv::formatReply(r, buf, sizeof buf);
      break;
    }
    case Gen::Endstops: {
      static const char kX[] UV_FLASH = "x_min: ", kY[] UV_FLASH = "y_min: ", kZ[] UV_FLASH = "z_min: ", kProbe[] UV_FLASH = "z_probe: ";
      static const char* const kNames[] UV_FLASH = {kX, kY, kZ, kProbe};
      if (long_.index >= 4) return false;
      bool closed = long_.index < 3 ? (io_.endstops() & (1 << long_.index)) : head_.probeTriggered();
      strcpy_flash(buf, uvFlashPtr(kNames[long_.index]));
      strcpy_flash(buf + strlen(buf), closed ? UV_P("TRIGGERED") : UV_P("open"));
      break;
    }
    case Gen::Files: {
      if (long_.index == 0) {
        strcpy_flash(buf, UV_P("Begin file list"));
      } else if (long_.index == 1) {
        uint32_t size;
        char name[kFileNameMax + 1];
        do {
          if (!sd_.entry(long_.fileIndex++, name, size)) {
            long_.index = 2;
            return true;
          }
        } while (isWorkFile(name));
        size_t n = strlen(name);
        memcpy(buf, name, n);
        buf[n] = ' ';
        buf[n + 1 + uv::putUnsigned(size, buf + n + 1)] = 0;
        if (!port.report(buf)) long_.fileIndex--;  // the same file next pass
        return true;
      } else if (long_.index == 2) {
        strcpy_flash(buf, UV_P("End file list"));
      } else {
        return false;
      }
      break;
    }
    case Gen::Mesh:
      if (!emitMesh(buf)) return false;
      break;
    case Gen::Config: {
      if (long_.index >= kKeyCount) return false;
      uvMemcpyP(buf, UV_P("M850 "), 5);
      uint8_t n = static_cast<uint8_t>(5 + keyName(static_cast<Key>(long_.index), buf + 5));
      buf[n++] = ' ';
      config_.format(static_cast<Key>(long_.index), buf + n);
      break;
    }
  }
  if (!port.report(buf)) return true;  // no room yet: the same line next pass
  long_.index++;
  return true;
}

void Machine::runLong() {
  if (long_.op != Op::Emit && long_.op != Op::Answer && static_cast<int32_t>(now_ - long_.keepalive) >= 0) {
    long_.keepalive = now_ + kKeepaliveUs;
    if (long_.port) long_.port->reportP(UV_P("busy: processing"));
    for (HostLink* p : ports_)  // a host waiting behind this command must not take the wait for a lost line
      if (p != long_.port && p->queued()) p->reportP(UV_P("busy: processing"));
  }
  switch (long_.op) {
    case Op::Emit:
      while (long_.port->room() >= kReplyRoom)
        if (!emitNext()) return finishLong();
      return;
    case Op::Answer:
      if (long_.port->room() >= kReplyRoom) finishLong(long_.error, long_.detail[0] ? long_.detail : nullptr);
      return;
    case Op::Dwell:
      if (now_ - long_.since >= long_.until) finishLong();
      return;
    case Op::MoveRoom:
      if (motion_.moveTo(long_.target, long_.feed)) finishLong();
      return;
    case Op::Probe: return runProbe();
    case Op::Level: return runLevel();
    case Op::Plan:
      if (!plan()->step(kPlanStopsPerPass)) return;
      if (plan()->error()) {
        uint8_t err = plan()->error();
        clearArena();
        jobState_ = uv::JobState::Failed;
        return finishLong(err);
      }
      clearArena();
      jobState_ = uv::JobState::Ready;
      if (!preparedSelect_) long_.port->lineP(UV_P("echo:Done saving file."));
      preparedSelect_ = false;
      return finishLong();
    case Op::Prepare: {
      if (!spool()->prepareStep(kPrepareLinesPerPass)) return;
      uint8_t err = spool()->finish();
      if (err) {
        char detail[16];
        uvMemcpyP(detail, UV_P("line "), 5);
        detail[5 + uv::putUnsigned(spool()->errorLine(), detail + 5)] = 0;
        clearArena();
        selected_[0] = 0;
        return finishLong(err, err == uv::kJobMalformed ? detail : nullptr);
      }
      uv::JobHeader header = spool()->header();
      preparedSelect_ = true;
      err = startPlanning(header);
      if (err) {
        planRefused(*long_.port, err);
        long_.port->ok();
        long_.op = Op::None;
        return;
      }
      long_.op = Op::Plan;
      return;
    }
    case Op::Release:
      if (!motion_.idle()) return;
      io_.motorsEnabled(false);
      homed_ = 0;
      return finishLong();
    case Op::Home: {
      RoutineStatus s = homing_.poll(io_.endstops());
      homed_ = static_cast<uint8_t>(homed_ | homing_.homed());
      if (s == RoutineStatus::Failed) {
        char axis[2] = {static_cast<char>('X' + homing_.failedAxis()), 0};
        return finishLong(homing_.error(), axis);
      }
      if (s == RoutineStatus::Done) finishLong();
      return;
    }
    case Op::SelfTest: {
      if (test_.poll() != RoutineStatus::Done) return;
      char buf[80];
      test_.format(buf);
      long_.port->line(buf);
      return finishLong(test_.allPass() ? 0 : uv::kSelftestFailed);
    }
    case Op::Servo:
      // The servo needs its time to move, then P tells whether the probe raised its alarm.
      if (static_cast<int32_t>(now_ - long_.until) < 0) return;
      if (long_.servoOp) {
        head_.requestProbe();
        long_.servoOp = 0;
        return;
      }
      if (!head_.online()) return finishLong(uv::kNanoTimeout);
      if (!head_.probeAnswered()) return;
      if (head_.probeTriggered() && long_.index == 'D') {
        deployed_ = false;
        long_.port->lineP(UV_P("PROBE:alarm"));
        return finishLong(uv::kProbeAlarm);
      }
      deployed_ = long_.index == 'D';
      long_.port->lineP(long_.index == 'D' ? UV_P("PROBE:deployed") : UV_P("PROBE:stowed"));
      return finishLong();
    case Op::ProbeRead:
      if (!head_.online()) {
        long_.op = Op::Emit;  // report the switches anyway; the probe reads as its last state
        long_.gen = Gen::Endstops;
        long_.index = 0;
        return;
      }
      if (!head_.probeAnswered()) return;
      long_.op = Op::Emit;
      long_.gen = Gen::Endstops;
      long_.index = 0;
      return;
    default:
      return;
  }
}

Machine::Result Machine::diagnostics(HostLink& port, const uv::Command& c) {
  char buf[112];
  char* p = buf;
  auto field = [&p](const char* flashName, uint32_t v) {
    size_t n = uvStrlenP(flashName);
    uvMemcpyP(p, flashName, n);
    p += n;
    p += uv::putUnsigned(v, p);
  };
  uint16_t dropped = 0, unsent = 0;
  for (HostLink* h : ports_) {
    dropped = static_cast<uint16_t>(dropped + h->dropped());
    unsent = static_cast<uint16_t>(unsent + h->txDropped());
  }
  field(UV_P("echo:DIAG loop_max_us="), stats_.loopMaxUs);
  field(UV_P(" step_isr_max_us="), stats_.stepIsrMaxUs);
  field(UV_P(" underruns="), motion_.engine().underruns());
  field(UV_P(" rx_dropped="), dropped);
  field(UV_P(" tx_dropped="), unsent);
  *p = 0;
  port.line(buf);
  if (c.has('R')) stats_.loopMaxUs = 0;
  return Result::Done;
}

void Machine::printheadEvents() {
  uint8_t e = head_.takeEvents();
  if (e & PrintheadLink::kWentOffline) {
    headFaults_.owed |= HeadFaults::kOffline * kAllPorts;
    lastFault_ = uv::kNanoTimeout;
  }
  if (e & PrintheadLink::kCameBack) broadcastP(UV_P("echo:printhead answering again"));
  if (e & PrintheadLink::kNanoReset) broadcastP(UV_P("echo:printhead restarted by its watchdog"));
  if (e & PrintheadLink::kFault) {
    head_.allOff();
    uint8_t active = head_.activeFaults();
    lastFault_ = (active & uv::fault::kSensor) ? uv::kSensorFault : uv::kOverTemperature;
    const int16_t* t = head_.deciC();
    uint8_t hot = 0;
    for (uint8_t i = 1; i < uv::kSensorCount; i++)
      if (t[i] > t[hot]) hot = i;
    headFaults_.sensor = (active & uv::fault::kSensor) != 0;
    headFaults_.hot = hot;
    headFaults_.deciC = t[hot];  // as it was when the fault came: the line may wait for room
    headFaults_.owed |= HeadFaults::kThermal * kAllPorts;
  }
  sayHeadFaults();
}

void Machine::sayHeadFaults() {
  // A FAULT line is never lost: it waits, per port, until that port has room for it whole.
  for (uint8_t k = 0; headFaults_.owed && k < kPorts; k++) {
    for (uint8_t kind = HeadFaults::kOffline; kind <= HeadFaults::kThermal; kind = static_cast<uint8_t>(kind << kPorts)) {
      uint8_t bit = static_cast<uint8_t>(kind << k);
      if (!(headFaults_.owed & bit)) continue;
      char buf[48];
      if (kind == HeadFaults::kOffline) {
        strcpy_flash(buf, UV_P("FAULT:E30 printhead not responding"));
      } else if (headFaults_.sensor) {
        strcpy_flash(buf, UV_P("FAULT:E32 temperature sensor fault"));
      } else {
        strcpy_flash(buf, UV_P("FAULT:E31 over-temperature T"));
        size_t n = strlen(buf);
        buf[n++] = static_cast<char>('0' + headFaults_.hot);
        buf[n++] = ' ';
        buf[n + uv::formatDeciC(headFaults_.deciC, buf + n)] = 0;
      }
      if (ports_[k]->report(buf)) headFaults_.owed = static_cast<uint8_t>(headFaults_.owed & ~bit);
    }
  }
}

uint8_t Machine::formatTemps(char* out) const {
  uv::Reply r{};
  r.kind = uv::ReplyKind::Temps;
  for (uint8_t i = 0; i < uv::kSensorCount; i++) {
    r.deciC[i] = head_.deciC()[i];
    r.limitDeciC[i] = static_cast<int16_t>(config_.milli(Key::ThermalLimit0 + i) / 100);
  }
  return static_cast<uint8_t>(uv::formatReply(r, out, 112));
}

uint8_t Machine::formatPosition(char* out) const {
  uv::Reply r{};
  r.kind = uv::ReplyKind::Position;
  int32_t steps[3];
  motion_.positionSteps(steps);
  for (uint8_t a = 0; a < 3; a++) {
    r.steps[a] = steps[a];
    r.um[a] = motion_.toUm(a, steps[a]);
  }
  return static_cast<uint8_t>(uv::formatReply(r, out, 112));
}

void Machine::reports() {
  char buf[112];
  if (tempPeriodUs_ && static_cast<int32_t>(now_ - tempNext_) >= 0 && head_.tempsKnown()) {
    tempNext_ = now_ + tempPeriodUs_;
    formatTemps(buf);
    broadcast(buf);
  }
  if (posPeriodUs_ && static_cast<int32_t>(now_ - posNext_) >= 0) {
    posNext_ = now_ + posPeriodUs_;
    formatPosition(buf);
    broadcast(buf);
  }
}

}  // namespace mega
