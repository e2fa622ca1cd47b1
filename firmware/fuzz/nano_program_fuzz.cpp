// Fuzzes the printhead's scan programs with well-formed chains that the fuzzer then breaks: lines
// dropped, repeated, reordered or with a byte changed, G, R, Q and hot sensors in between, while
// the chain plays out. Holds: no LED stays on longer than the cap, in a program or across a chain;
// a chain ends with every LED off; nothing is lit after R or under a thermal fault; every K and Q
// answer is one the protocol has.
#include <fuzzer/FuzzedDataProvider.h>

#include <string>
#include <vector>

#include "fuzz_checks.h"
#include "printhead.h"
#include "scan_program.h"

namespace {

constexpr uint32_t kCapUs = 50000;  // small, so random chains reach it

struct Board : nano::PrintheadIo {
  uint8_t lit = 0;
  nano::ScanStore* chain = nullptr;
  uint32_t on[4] = {};  // how long each lit LED has been on, µs
  std::string out;
  void fire(const nano::FirePlan& p) override { lit = p.onMask; }
  void allOff() override {
    lit = 0;
    chain = nullptr;
  }
  uint8_t litMask() const override { return lit; }
  uint32_t clockLineUs() override { return 0; }
  bool takeCut(int32_t&) override { return false; }  // cuts are not modelled here: no dose record is checked
  bool startProgram(nano::ScanStore& s) override {
    chain = &s;
    for (uint32_t& t : on) t = 0;
    return true;
  }
  void servoPulse(uint16_t) override {}
  bool probeTriggered() override { return false; }
  void reply(const char* t, uint8_t n) override { out.append(t, n); }
  void linkSpeed(uint32_t, bool) override {}
  // The timer's work: up to `events` of the running chain; an F's LEDs (a changed byte can make
  // one) go off in their own time.
  void play(uint16_t events) {
    if (!chain) lit = 0;
    while (chain && events--) {
      uint32_t d;
      uint8_t m;
      nano::ScanStore::Step s = chain->next(d, m);
      if (s != nano::ScanStore::Step::Event) {
        lit = 0;  // the end of the chain, or an underrun: the runner writes every LED off
        chain = nullptr;
        return;
      }
      for (uint8_t k = 0; k < 4; k++) {
        if (lit >> k & 1) on[k] += d;
        FUZZ_REQUIRE(on[k] <= kCapUs, "an LED kept on past the cap by a chain");
        if (!(m >> k & 1)) on[k] = 0;
      }
      lit = m;
    }
  }
};

// The chain's events, drawn from the fuzzer's bytes as the Mega's planner would hand them out.
struct Draw {
  FuzzedDataProvider& in;
  uint16_t left;  // events still to hand out; the last one puts every LED off
  uint32_t t;     // the first event's time, then the last one's
  bool started = false;
  static bool take(void* ctx, uint32_t& t, uint8_t& m) {
    auto* d = static_cast<Draw*>(ctx);
    if (!d->left) return false;
    if (d->started) d->t += d->left == 1 ? 1 : d->in.ConsumeIntegralInRange<uint32_t>(1, 30000);
    d->started = true;
    d->left--;
    t = d->t;
    m = d->left ? d->in.ConsumeIntegralInRange<uint8_t>(0, 15) : 0;
    return true;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  // A chain as the Mega would write it: events at rising times, possibly long and lit.
  Draw draw{in, in.ConsumeIntegralInRange<uint16_t>(2, 201), in.ConsumeIntegralInRange<uint32_t>(0, 10)};
  uv::ProgramLines writer(Draw::take, &draw);
  std::vector<std::string> lines;
  char out[uv::kNanoMaxLine + 2];
  while (uint8_t len = writer.next(out)) lines.emplace_back(out, len - 1);

  Board board;
  const nano::PrintheadConfig config = {kCapUs, {{600, 600, 600, 600, 600, 600}, 50, 100, 1750}, "0.2.0"};
  nano::Printhead head(board, config);
  uint16_t cool[6] = {750, 750, 750, 750, 750, 750};
  head.readings(cool);
  size_t next = 0;
  auto send = [&](std::string line) {
    head.line(line.data(), static_cast<uint8_t>(line.size() > 255 ? 255 : line.size()), line.size() > uv::kNanoMaxLine, 0);
  };
  while (in.remaining_bytes()) {
    switch (in.ConsumeIntegralInRange<uint8_t>(0, 9)) {
      case 0: case 1: case 2:  // the next line as written
        if (next < lines.size()) send(lines[next++]);
        break;
      case 3:  // dropped
        if (next < lines.size()) next++;
        break;
      case 4:  // repeated, or an earlier one again
        if (next) send(lines[in.ConsumeIntegralInRange<size_t>(0, next - 1)]);
        break;
      case 5:  // a byte changed
        if (next < lines.size()) {
          std::string l = lines[next++];
          l[in.ConsumeIntegralInRange<size_t>(0, l.size() - 1)] = static_cast<char>(in.ConsumeIntegralInRange<uint8_t>(0x20, 0x7e));
          send(l);
        }
        break;
      case 6:
        send("G");
        break;
      case 7:
        send("R");
        FUZZ_REQUIRE(board.lit == 0 && !board.chain, "an LED lit or a chain running after R");
        break;
      case 8: {  // a sweep, sometimes hot
        uint16_t mv[6];
        for (uint16_t& m : mv) m = in.ConsumeBool() ? 750 : in.ConsumeIntegralInRange<uint16_t>(0, 5500);
        head.readings(mv);
        if (head.faults() & uv::fault::kActive) FUZZ_REQUIRE(board.lit == 0 && !board.chain, "an LED lit under a thermal fault");
        break;
      }
      case 9:
        board.play(in.ConsumeIntegralInRange<uint16_t>(1, 80));
        send("Q");
        break;
    }
    for (std::string& l : fuzz::takeLines(board.out)) {
      std::string withEnd = l + "\n";
      uv::NanoReply r{};
      FUZZ_REQUIRE(uv::parseNanoReply(withEnd.data(), withEnd.size(), r), ("a reply the Mega cannot parse: " + l).c_str());
    }
  }
  board.play(0xffff);
  FUZZ_REQUIRE(board.lit == 0, "a chain that ended with an LED on");
  return 0;
}
