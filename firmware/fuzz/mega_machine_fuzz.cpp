// Fuzzes the Mega's whole command core: bytes from both hosts, at the wire's pace, into the real
// machine (motion, jobs, probe, config, card, EEPROM) with the real Nano logic behind it, which
// may heat up or go silent. Holds: every line to a host is whole and known; no LED is lit while
// the machine is halted or after an over-temperature; no reply is ever dropped.
#include <fuzzer/FuzzedDataProvider.h>

#include <memory>
#include <string>

#include "fuzz_checks.h"
#include "mega_rig.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  auto rig = std::make_unique<mega::MegaRig>();  // a fresh machine, card and EEPROM per input
  mega::MegaRig& m = *rig;
  m.begin();
  std::string halted = "Error:E13";
  int steps = 0;
  while (in.remaining_bytes() && steps++ < 64) {
    switch (in.ConsumeIntegralInRange<uint8_t>(0, 4)) {
      case 0:
        m.usb.toMega += in.ConsumeRandomLengthString(100);
        break;
      case 1:
        m.esp.toMega += in.ConsumeRandomLengthString(100);
        break;
      case 2:  // a well-formed numbered line, so fuzzing reaches the commands behind the framing
        m.send(in.ConsumeRandomLengthString(60), in.ConsumeBool());
        break;
      case 3:
        m.nano.setTemps(in.ConsumeIntegralInRange<int16_t>(-500, 1300));
        break;
      case 4:
        m.nano.silent = in.ConsumeBool();
        break;
    }
    m.run(in.ConsumeIntegralInRange<uint32_t>(100, 20000));
    uint8_t lit = m.nano.lit();
    for (const std::vector<std::string>* lines : {&m.usbLines, &m.espLines}) {
      for (const std::string& l : *lines) {
        fuzz::requireHostLine(l);
        if (l.rfind(halted, 0) == 0) FUZZ_REQUIRE(lit == 0, "an LED lit while the machine is halted");
      }
    }
    m.usbLines.clear();
    m.espLines.clear();
  }
  FUZZ_REQUIRE(m.usbLink.txDropped() == 0 && m.espLink.txDropped() == 0, "a reply dropped");
  return 0;
}
