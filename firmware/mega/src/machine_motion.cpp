// Motion commands of the command core: G0/G1 with soft limits and a modal feed rate, G4 and M400, G28, M18,
// M820 jog, M822, M113.
#include "error_codes.h"
#include "machine.h"
#include "progmem.h"
#include "text_scan.h"

namespace mega {

namespace {
const Key kBed[3] = {Key::BedX, Key::BedY, Key::BedZ};
const char kAxis[3] = {'X', 'Y', 'Z'};
// Axis names as error details (RAM strings: errorLine copies them).
const char kAxisName[3][2] = {"X", "Y", "Z"};
}  // namespace

Machine::Result Machine::move(HostLink& port, const uv::Command& c) {
  int32_t base[3], to[3];
  motion_.targetUm(base);  // where the queued moves end: relative moves add to it
  for (uint8_t a = 0; a < 3; a++) {
    to[a] = base[a];
    if (!c.has(kAxis[a])) continue;
    if (!c.hasValue(kAxis[a])) {
      port.errorLine(uv::kBadParameter, kAxisName[a]);
      return Result::Done;
    }
    if (!axisHomed(a)) {
      port.errorLine(uv::kNotHomed, kAxisName[a]);
      return Result::Done;
    }
    to[a] = absolute_ ? c.value(kAxis[a]) : base[a] + c.value(kAxis[a]);  // thousandths of mm = µm
  }
  for (uint8_t a = 0; a < 3; a++) {
    if (c.has(kAxis[a]) && (to[a] < 0 || to[a] > config_.milli(kBed[a]))) {
      port.errorLine(uv::kSoftLimit, kAxisName[a]);
      return Result::Done;
    }
  }
  if (c.hasValue('F')) {
    if (c.value('F') <= 0) {
      port.errorLineP(uv::kBadParameter, UV_P("F"));
      return Result::Done;
    }
    // Kept only once the move is accepted: a refused line leaves the machine as it was.
    feedUmS_ = static_cast<uint32_t>(c.value('F') / 60);  // mm/min in thousandths → µm/s
    if (!feedUmS_) feedUmS_ = 1;
  }
  uint32_t feed = feedUmS_;
  io_.motorsEnabled(true);
  if (motion_.moveTo(to, feed)) return Result::Done;  // a move answers once it is queued
  long_.op = Op::MoveRoom;
  for (uint8_t a = 0; a < 3; a++) long_.target[a] = to[a];
  long_.feed = feed;
  return Result::Long;
}

Machine::Result Machine::dwell(HostLink& port, const uv::Command& c) {
  // The wait is measured as time since it began, in unsigned µs, so any dwell up to 2^32 - 1 µs
  // (71 minutes) ends on time; a longer one is refused, never wrapped into a short one.
  constexpr int32_t kMaxDwellMs = 4294967;
  uint32_t us = 0;
  if (c.hasValue('P') && c.value('P') > 0) {
    us = static_cast<uint32_t>(c.value('P'));  // ms in thousandths = µs
  } else if (c.hasValue('S') && c.value('S') > 0) {
    if (c.value('S') > kMaxDwellMs) {  // s in thousandths = ms
      port.errorLineP(uv::kBadParameter, UV_P("S"));
      return Result::Done;
    }
    us = static_cast<uint32_t>(c.value('S')) * 1000;
  }
  long_.op = Op::Dwell;
  long_.since = now_;
  long_.until = us;    // for a dwell: its length
  long_.drain = true;  // after the moves before it, as Marlin's G4
  return Result::Long;
}

Machine::Result Machine::drain(HostLink&, const uv::Command&) {
  long_.op = Op::Dwell;
  long_.until = 0;
  long_.drain = true;
  return Result::Long;
}

Machine::Result Machine::busyInterval(HostLink& port, const uv::Command& c) {
  uint8_t k = &port == ports_[0] ? 0 : 1;
  if (!c.has('S')) {
    char buf[16];
    uvMemcpyP(buf, UV_P("echo:M113 S"), 11);
    buf[11 + uv::putUnsigned(keepaliveS_[k], buf + 11)] = 0;
    port.line(buf);
    return Result::Done;
  }
  int32_t s = c.hasValue('S') ? c.value('S') : -1;  // seconds in thousandths
  if (s < 0 || s > static_cast<int32_t>(kKeepaliveMaxS) * 1000 || s % 1000) {
    port.errorLineP(uv::kBadParameter, UV_P("S"));
    return Result::Done;
  }
  keepaliveS_[k] = static_cast<uint8_t>(s / 1000);
  return Result::Done;
}

Machine::Result Machine::home(HostLink&, const uv::Command& c) {
  uint8_t axes = 0;
  for (uint8_t a = 0; a < 3; a++)
    if (c.has(kAxis[a])) axes = static_cast<uint8_t>(axes | (1 << a));
  if (!axes) axes = 7;
  long_.op = Op::Home;
  long_.index = axes;  // homing starts once the queued moves have ended (runLong)
  long_.drain = true;
  return Result::Long;
}

Machine::Result Machine::release(HostLink&, const uv::Command&) {
  long_.op = Op::Release;
  long_.drain = true;  // the queued moves end first, as Marlin's M18/M84: the head stops where they end
  return Result::Long;
}

Machine::Result Machine::jog(HostLink& port, const uv::Command& c) {
  int8_t axis = -1;
  for (uint8_t a = 0; a < 3; a++) {
    if (!c.has(kAxis[a])) continue;
    if (axis >= 0 || !c.hasValue(kAxis[a]) || (c.value(kAxis[a]) != 1000 && c.value(kAxis[a]) != -1000)) axis = 4;
    else axis = static_cast<int8_t>(a);
  }
  bool fast = c.hasValue('S') && c.value('S') == 1000;
  if (axis < 0 || axis > 2 || (c.hasValue('S') && c.value('S') != 0 && !fast)) {
    port.errorLine(uv::kBadParameter);
    return Result::Done;
  }
  if (!axisHomed(static_cast<uint8_t>(axis))) {
    port.errorLine(uv::kNotHomed, kAxisName[axis]);
    return Result::Done;
  }
  int32_t to[3];
  motion_.positionUm(to);
  to[axis] = c.value(kAxis[axis]) > 0 ? config_.milli(kBed[axis]) : 0;  // on until M410 or the soft limit
  long_.feed = static_cast<uint32_t>(config_.milli(fast ? Key::SpeedJogFast : Key::SpeedJogSlow));
  io_.motorsEnabled(true);
  if (motion_.idle() && motion_.moveTo(to, long_.feed)) return Result::Done;
  motion_.stop();  // a new jog replaces the one running
  long_.op = Op::MoveRoom;
  for (uint8_t a = 0; a < 3; a++) long_.target[a] = to[a];
  return Result::Long;
}

Machine::Result Machine::selfTest(HostLink& port, const uv::Command& c) {
  if (!axisHomed(0) || !axisHomed(1)) {
    port.errorLineP(uv::kNotHomed, UV_P("home first (G28)"));
    return Result::Done;
  }
  if (!motion_.idle()) return Result::Wait;
  test_.start(c.has('Q'));
  long_.op = Op::SelfTest;
  return Result::Long;
}

Machine::Result Machine::absoluteMode(HostLink&, const uv::Command&) {
  absolute_ = true;
  return Result::Done;
}

Machine::Result Machine::relativeMode(HostLink&, const uv::Command&) {
  absolute_ = false;
  return Result::Done;
}

Machine::Result Machine::motorsOn(HostLink&, const uv::Command&) {
  io_.motorsEnabled(true);
  return Result::Done;
}

Machine::Result Machine::quickStop(HostLink&, const uv::Command&) {
  motion_.stop();
  return Result::Done;
}

Machine::Result Machine::position(HostLink& port, const uv::Command&) {
  char buf[112];
  formatPosition(buf);
  port.line(buf);
  return Result::Done;
}

}  // namespace mega
