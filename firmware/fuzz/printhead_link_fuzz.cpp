// Fuzzes the Mega's side of the printhead link with whatever the Nano's UART might deliver:
// replies, noise, silence, cut lines. Holds: every line the Mega sends the Nano is a command of
// the table (nano.md) and parses; after allOff the next line out is R; temperatures stay in
// what T: can carry; the firmware name is printable and bounded.
#include <fuzzer/FuzzedDataProvider.h>

#include <string>

#include "fuzz_checks.h"
#include "printhead_link.h"

namespace {

struct Uart : mega::ByteStream {
  std::string rx, tx;
  int16_t read() override {
    if (rx.empty()) return -1;
    uint8_t b = static_cast<uint8_t>(rx[0]);
    rx.erase(0, 1);
    return b;
  }
  bool write(const char* data, uint8_t n) override {
    if (tx.size() + n > 64) return false;  // the UART's buffer: whole writes or none
    tx.append(data, n);
    return true;
  }
  bool writeNow(char op, uint32_t& atUs) override {
    if (!tx.empty()) return false;  // the transmitter is busy
    tx.push_back(op);
    tx.push_back('\n');
    atUs = ++clockUs;
    return true;
  }
  bool setBaud(uint32_t) override { return tx.empty(); }  // the transmitter idle
  uint32_t clockUs = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  Uart uart;
  mega::PrintheadLink link(uart);
  uint32_t now = in.ConsumeIntegral<uint32_t>();
  link.begin(now);
  bool expectR = false;
  while (in.remaining_bytes()) {
    switch (in.ConsumeIntegralInRange<uint8_t>(0, 5)) {
      case 0:
        uart.rx += in.ConsumeRandomLengthString(60);
        break;
      case 1: {
        uint32_t us[uv::kLedCount];
        for (uint32_t& u : us) u = in.ConsumeIntegralInRange<uint32_t>(0, 20000000);
        link.fire(in.ConsumeIntegral<uint8_t>(), us, now);
        break;
      }
      case 2:
        link.allOff(in.ConsumeIntegral<uint8_t>());
        expectR = true;
        break;
      case 3:
        link.servo(in.PickValueInArray({'D', 'U', 'X'}));
        break;
      case 4:
        if (in.ConsumeBool()) link.requestProbe();
        else link.requestCounters();
        break;
      case 5:
        now += in.ConsumeIntegralInRange<uint32_t>(0, 200000);
        break;
    }
    link.poll(now);
    for (const std::string& l : fuzz::takeLines(uart.tx)) {
      uv::NanoCommand c;
      FUZZ_REQUIRE(fuzz::printable(l) && l.size() <= uv::kNanoMaxLine, ("a line to the Nano out of form: " + l).c_str());
      FUZZ_REQUIRE(uv::parseNanoCommand(l.data(), static_cast<uint8_t>(l.size()), c), ("a line the Nano cannot parse: " + l).c_str());
      if (expectR) FUZZ_REQUIRE(l == "R", ("allOff sent something before R: " + l).c_str());
      expectR = false;
    }
    uart.tx.clear();  // the Nano took it
    for (uint8_t i = 0; i < uv::kSensorCount; i++)
      FUZZ_REQUIRE(link.deciC()[i] >= -9999 && link.deciC()[i] <= 9999, "a temperature T: cannot carry (nano.md: -999.9 to 999.9)");
    std::string name = link.firmware();
    FUZZ_REQUIRE(fuzz::printable(name) && name.size() <= 40, "a firmware name out of form");
  }
  return 0;
}
