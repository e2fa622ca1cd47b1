// The command core's long commands, polled once a main-loop pass until each ends (protocol/mega.md §5
// "long" commands): dwell and waiting for the queue, homing, the self-test, the probe servo, planning.
#include <string.h>

#include "error_codes.h"
#include "job_files.h"
#include "machine.h"
#include "machine_budget.h"
#include "progmem.h"
#include "text_scan.h"

namespace mega {

void Machine::runLong() {
  if (long_.op != Op::Emit && long_.op != Op::Answer && static_cast<int32_t>(now_ - long_.keepalive) >= 0) {
    uint32_t every = keepaliveUs(long_.port);
    long_.keepalive = now_ + (every ? every : kKeepaliveUs);
    if (long_.port && every) long_.port->reportP(UV_P("busy: processing"));
    for (HostLink* p : ports_)  // a host waiting behind this command must not take the wait for a lost line
      if (p != long_.port && p->queued() && keepaliveUs(p)) p->reportP(UV_P("busy: processing"));
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
      if (long_.drain) {  // the dwell starts when the last queued move has ended
        if (!motion_.idle()) return;
        long_.drain = false;
        long_.since = now_;
      }
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
        // Nothing half-planned stays to be started: the job's text does, to be selected again.
        removeWorkFiles(sd_, selected_);
        selected_[0] = 0;
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
        preparedSelect_ = false;  // else the next upload's M29 would not say "Done saving file."
        planRefused(*long_.port, err);
        long_.port->ok();
        long_.op = Op::None;
        return;
      }
      long_.op = Op::Plan;
      return;
    }
    case Op::Store:  // M500: its answer once the EEPROM holds the settings
      if (store_.saving() || long_.port->room() < kReplyRoom) return;
      long_.port->lineP(sd_.present() ? UV_P("echo:Settings stored") : UV_P("echo:Settings stored in EEPROM only: no SD card"));
      return finishLong();
    case Op::Release:
      if (long_.drain) {  // the moves queued before M18/M84 end first, where they were sent (Marlin)
        if (!motion_.idle()) return;
        long_.drain = false;
      }
      io_.motorsEnabled(false);
      homed_ = 0;
      return finishLong();
    case Op::Home: {
      if (long_.drain) {  // the moves queued before G28 end first, as in Marlin
        if (!motion_.idle()) return;
        long_.drain = false;
        homed_ = static_cast<uint8_t>(homed_ & ~long_.index);
        io_.motorsEnabled(true);
        homing_.start(long_.index);
      }
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


}  // namespace mega
