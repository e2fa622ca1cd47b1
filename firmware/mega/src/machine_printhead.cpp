// Printhead commands of the command core: M105, M401/M402/M280 (the CR Touch), M355 (the work light).
#include "error_codes.h"
#include "machine.h"
#include "progmem.h"

namespace mega {


Machine::Result Machine::temperatures(HostLink& port, const uv::Command&) {
  if (head_.firstReadingDue()) return Result::Wait;
  if (!head_.online() || !head_.tempsKnown()) {
    port.errorLine(uv::kNanoTimeout);
    return Result::Done;
  }
  char buf[112];
  formatTemps(buf);
  port.line(buf);
  return Result::Done;
}

Machine::Result Machine::servo(HostLink& port, const uv::Command& c, char op) {
  if (!op) {  // M280 P0 S<angle>: 10 deploy, 90 stow, 160 alarm release
    int32_t s = c.hasValue('S') ? c.value('S') : -1;
    op = s == 10000 ? 'D' : s == 90000 ? 'U' : s == 160000 ? 'X' : 0;
    if (!c.hasValue('P') || c.value('P') != 0 || !op) {
      port.errorLine(uv::kBadParameter);
      return Result::Done;
    }
  }
  if (!head_.online()) {
    port.errorLine(uv::kNanoTimeout);
    return Result::Done;
  }
  if (!head_.servo(op)) return Result::Wait;
  long_.op = Op::Servo;
  long_.until = now_ + kServoSettleUs;
  long_.servoOp = op;  // cleared once P is asked
  long_.index = static_cast<uint8_t>(op);
  return Result::Long;
}

Machine::Result Machine::light(HostLink& port, const uv::Command& c) {
  bool on = c.hasValue('S') ? c.value('S') != 0 : true;
  if (!io_.light(static_cast<uint8_t>(config_.whole(Key::LightPin)), on)) {
    port.errorLineP(uv::kBadParameter, UV_P("light.pin is not a free pin"));
    return Result::Done;
  }
  lightOn_ = on;
  return Result::Done;
}

Machine::Result Machine::deployProbe(HostLink& port, const uv::Command& c) { return servo(port, c, 'D'); }
Machine::Result Machine::stowProbe(HostLink& port, const uv::Command& c) { return servo(port, c, 'U'); }
Machine::Result Machine::servoAngle(HostLink& port, const uv::Command& c) { return servo(port, c, 0); }

Machine::Result Machine::endstops(HostLink&, const uv::Command&) {
  long_.op = Op::ProbeRead;
  head_.requestProbe();
  return Result::Long;
}

}  // namespace mega
