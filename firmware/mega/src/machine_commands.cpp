// The Mega's command table: every G and M command, when it may run beyond its turn, and the member
// that runs it; the dispatch from it, and the few commands of the core itself.
#include "machine.h"

#include "error_codes.h"
#include "progmem.h"
#include "text_scan.h"

namespace mega {

// In flash: 8 bytes a row on the AVR (a member pointer is 4). Looked up by a walk, once a command, that
// reads a row's letter and code and copies out only the row that matches.
const Machine::CommandRow Machine::kCommands[] UV_FLASH = {
    {'G', 0, 0, &Machine::move},
    {'G', 1, 0, &Machine::move},
    {'G', 4, 0, &Machine::dwell},
    {'G', 28, 0, &Machine::home},
    {'G', 29, 0, &Machine::level},
    {'G', 30, 0, &Machine::probeOnce},
    {'G', 90, 0, &Machine::absoluteMode},
    {'G', 91, 0, &Machine::relativeMode},
    {'M', 17, 0, &Machine::motorsOn},
    {'M', 18, 0, &Machine::release},
    {'M', 20, 0, &Machine::jobCommand},
    {'M', 21, 0, &Machine::cardInit},
    {'M', 23, 0, &Machine::jobCommand},
    {'M', 24, kStream, &Machine::jobCommand},
    {'M', 25, kStream, &Machine::jobCommand},
    {'M', 26, 0, &Machine::jobCommand},
    {'M', 27, kQuery | kStream, &Machine::jobCommand},
    {'M', 28, 0, &Machine::jobCommand},
    {'M', 29, 0, &Machine::jobCommand},
    {'M', 30, 0, &Machine::jobCommand},
    {'M', 32, 0, &Machine::jobCommand},
    {'M', 84, 0, &Machine::release},
    {'M', 105, kQuery | kStream, &Machine::temperatures},
    {'M', 108, 0, &Machine::nothing},  // Marlin's "stop waiting for heaters": nothing here heats or waits for heat
    {'M', 110, 0, &Machine::refuseM110},
    {'M', 112, kWhileHalted, &Machine::nothing},  // acted on when it arrived
    {'M', 113, 0, &Machine::busyInterval},
    {'M', 114, kQuery | kStream, &Machine::position},
    {'M', 115, kQuery | kStream, &Machine::firmwareInfo},
    {'M', 117, 0, &Machine::message},
    {'M', 119, 0, &Machine::endstops},
    {'M', 154, kQuery | kStream, &Machine::reportPeriod},
    {'M', 155, kQuery | kStream, &Machine::reportPeriod},
    {'M', 280, 0, &Machine::servoAngle},
    {'M', 355, 0, &Machine::light},
    {'M', 400, 0, &Machine::drain},
    {'M', 401, 0, &Machine::deployProbe},
    {'M', 402, 0, &Machine::stowProbe},
    {'M', 410, 0, &Machine::quickStop},
    {'M', 420, 0, &Machine::meshCommand},
    {'M', 500, 0, &Machine::configCommand},
    {'M', 501, 0, &Machine::configCommand},
    {'M', 502, 0, &Machine::configCommand},
    {'M', 503, 0, &Machine::configCommand},
    {'M', 524, kStream, &Machine::jobCommand},
    {'M', 820, 0, &Machine::jog},
    {'M', 821, 0, &Machine::diagnostics},
    {'M', 822, 0, &Machine::selfTest},
    {'M', 828, 0, &Machine::jobCommand},
    {'M', 850, 0, &Machine::configCommand},
    {'M', 999, kWhileHalted, &Machine::leaveHalt},
    {'M', 1000, 0, &Machine::jobCommand},
};

bool Machine::findCommand(const uv::Command& c, CommandRow& row) {
  for (const CommandRow& r : kCommands) {
    if (static_cast<char>(uvFlashByte(&r.letter)) != c.letter) continue;
    uint16_t code;
    uvMemcpyP(&code, &r.code, sizeof code);
    if (code != c.code) continue;
    uvMemcpyP(&row, &r, sizeof row);
    return true;
  }
  return false;
}

uint8_t Machine::commandFlags(const uv::Command& c) {
  CommandRow row;
  return findCommand(c, row) ? row.flags : 0;
}

bool Machine::knows(const uv::Command& c) {
  CommandRow row;
  return findCommand(c, row);
}

Machine::Result Machine::dispatch(HostLink& port, const uv::Command& c) {
  CommandRow row;
  if (findCommand(c, row)) return (this->*row.run)(port, c);
  char word[8];
  word[0] = c.letter;
  word[1 + uv::putUnsigned(c.code, word + 1)] = 0;
  port.errorLine(uv::kUnknownCommand, word);
  return Result::Done;
}

Machine::Result Machine::firmwareInfo(HostLink&, const uv::Command&) {
  long_.op = Op::Emit;
  long_.gen = Gen::Firmware;
  long_.index = 0;
  return Result::Long;
}

Machine::Result Machine::reportPeriod(HostLink& port, const uv::Command& c) {
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

Machine::Result Machine::refuseM110(HostLink& port, const uv::Command&) {
  port.errorLine(uv::kBadParameter);  // the receiver takes every good M110
  return Result::Done;
}

Machine::Result Machine::nothing(HostLink&, const uv::Command&) { return Result::Done; }

Machine::Result Machine::cardInit(HostLink& port, const uv::Command&) {
  // Marlin's "init card": the card is mounted at start; say whether it is there
  port.lineP(sd_.present() ? UV_P("echo:SD card ok") : UV_P("echo:SD init fail"));
  return Result::Done;
}

Machine::Result Machine::leaveHalt(HostLink&, const uv::Command&) {
  halted_ = false;
  lastFault_ = 0;
  return Result::Done;
}

}  // namespace mega
