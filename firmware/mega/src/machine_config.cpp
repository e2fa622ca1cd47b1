// Config commands of the command core: M850 set/query, M500 save, M501 load, M502 defaults, M503 report.
#include <string.h>

#include "error_codes.h"
#include "machine.h"
#include "progmem.h"

namespace mega {

void Machine::stepsChanged(const int32_t before[3]) {
  for (uint8_t a = 0; a < 3; a++)
    if (config_.milli(Key::StepsX + a) != before[a]) homed_ = static_cast<uint8_t>(homed_ & ~(1 << a));
}

void Machine::applyConfig() {
  posPeriodUs_ = static_cast<uint32_t>(config_.whole(Key::ReportPositionMs)) * 1000;
  io_.invertDirections(static_cast<uint8_t>(config_.whole(Key::InvertX) | config_.whole(Key::InvertY) << 1 | config_.whole(Key::InvertZ) << 2));
}

Machine::Result Machine::configCommand(HostLink& port, const uv::Command& c) {
  int32_t steps[3] = {config_.milli(Key::StepsX), config_.milli(Key::StepsY), config_.milli(Key::StepsZ)};
  switch (c.code) {
    case 850: {
      Key key;
      bool query;
      Config next = config_;
      uint8_t err = applyM850(next, c.text, c.textLen, key, query);
      if (err) {
        port.errorLine(err, c.textLen ? c.text : nullptr);
        return Result::Done;
      }
      if (query) {
        char buf[48];
        uvMemcpyP(buf, UV_P("M850 "), 5);
        uint8_t n = static_cast<uint8_t>(5 + keyName(key, buf + 5));
        buf[n++] = ' ';
        config_.format(key, buf + n);
        port.line(buf);
        return Result::Done;
      }
      if (store_.saving()) return Result::Wait;  // the EEPROM copy is being written from these values
      config_ = next;
      break;
    }
    case 500: {
      if (jobActive()) {
        port.errorLine(uv::kBusy);
        return Result::Done;
      }
      uint8_t err = store_.save();
      if (err) port.errorLineP(err, UV_P("CONFIG.TXT"));
      long_.op = Op::Store;  // "stored" once the EEPROM copy is written: a power cut after it keeps them
      return Result::Long;
    }
    case 501:
      if (jobActive()) {
        port.errorLine(uv::kBusy);
        return Result::Done;
      }
      if (store_.saving()) return Result::Wait;
      store_.load();
      break;
    case 502:
      if (store_.saving()) return Result::Wait;
      config_.defaults();
      break;
    case 503:
      long_.op = Op::Emit;
      long_.gen = Gen::Config;
      long_.index = 0;
      return Result::Long;
  }
  stepsChanged(steps);
  applyConfig();
  return Result::Done;
}

}  // namespace mega
