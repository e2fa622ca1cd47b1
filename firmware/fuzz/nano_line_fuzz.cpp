// Fuzzes the Nano's command path as its UART feeds it: bytes through the line splitter into the
// printhead's brain, with sensor readings and time in between. Holds: every reply parses; no
// LED is lit after R or while a thermal fault is active; no LED is planned past the cap.
#include <fuzzer/FuzzedDataProvider.h>

#include <string>

#include "config.h"
#include "fuzz_checks.h"
#include "line_splitter.h"
#include "printhead.h"

namespace {

struct Io : nano::PrintheadIo {
  uint8_t lit = 0;
  uint32_t capUs = 0;
  std::string out;
  void fire(const nano::FirePlan& p) override {
    for (uint8_t i = 0; i < p.count; i++) FUZZ_REQUIRE(p.events[i].tick / nano::kTicksPerUs <= capUs, "an LED planned past the exposure cap");
    lit = p.onMask;
  }
  void allOff() override { lit = 0; }
  // A chain runs to its end at once; every event it hands out must be one the protocol allows.
  bool startProgram(nano::ScanStore& store) override {
    uint32_t d;
    uint8_t m, was = 0;
    uint64_t on[4] = {};
    while (store.next(d, m) == nano::ScanStore::Step::Event) {
      FUZZ_REQUIRE(m <= 15 && d <= uv::kProgramMaxDelta, "an event no program may hold");
      for (uint8_t i = 0; i < 4; i++) {
        if (was >> i & 1) on[i] += d;
        FUZZ_REQUIRE(on[i] <= capUs, "an LED kept on past the exposure cap by a program");
        if (!(m >> i & 1)) on[i] = 0;
      }
      was = m;
    }
    return true;
  }
  uint8_t litMask() const override { return lit; }
  uint32_t clockLineUs() override { return 0; }
  bool takeCut(int32_t&) override { return false; }  // cuts are not modelled here: no dose record is checked
  void servoPulse(uint16_t us) override { FUZZ_REQUIRE(us >= 500 && us <= 2500, "a servo pulse no CR Touch takes"); }
  bool probeTriggered() override { return false; }
  void reply(const char* t, uint8_t n) override { out.append(t, n); }
  void linkSpeed(uint32_t, bool) override {}
};

const nano::PrintheadConfig kConfig = {NANO_MAX_EXPOSURE_US, {NANO_TEMP_LIMITS_DC, NANO_TEMP_HYSTERESIS_DC, 100, 1750}, NANO_FIRMWARE_VERSION};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  Io io;
  io.capUs = kConfig.capUs;
  nano::Printhead head(io, kConfig);
  char buf[uv::kNanoMaxLine + 1];
  uv::LineSplitter splitter(buf, uv::kNanoMaxLine);
  uint32_t nowMs = in.ConsumeIntegral<uint32_t>();
  while (in.remaining_bytes()) {
    switch (in.ConsumeIntegralInRange<uint8_t>(0, 3)) {
      case 0: {  // bytes on the wire
        std::string bytes = in.ConsumeRandomLengthString(80);
        for (char c : bytes) {
          if (!splitter.push(c)) continue;
          std::string line(splitter.text(), splitter.length());
          bool overflow = splitter.overflow();
          head.line(splitter.text(), splitter.length(), overflow, nowMs);
          if (!overflow && line == "R") FUZZ_REQUIRE(io.lit == 0, "an LED lit after R");
        }
        break;
      }
      case 1: {  // a sweep of the six sensors, nonsense included
        uint16_t mv[uv::kSensorCount];
        for (uint16_t& m : mv) m = in.ConsumeIntegralInRange<uint16_t>(0, 5500);
        head.readings(mv);
        break;
      }
      case 2:
        nowMs += in.ConsumeIntegralInRange<uint32_t>(0, 100000);
        break;
      case 3:
        io.lit = 0;  // the LED timer's switch-offs
        break;
    }
    if (head.faults() & uv::fault::kActive) FUZZ_REQUIRE(io.lit == 0, "an LED lit while a thermal fault is active");
    for (std::string& l : fuzz::takeLines(io.out)) {
      std::string withEnd = l + "\n";
      uv::NanoReply r{};
      FUZZ_REQUIRE(fuzz::printable(l) && withEnd.size() <= uv::kNanoReplyMax, ("a reply out of form: " + l).c_str());
      FUZZ_REQUIRE(uv::parseNanoReply(withEnd.data(), withEnd.size(), r), ("a reply the Mega cannot parse: " + l).c_str());
    }
  }
  FUZZ_REQUIRE(io.out.empty(), "a reply without its line end");
  return 0;
}
