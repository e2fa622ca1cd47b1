// The printhead's answers to scan-program sessions (protocol/vectors/nano-program.json "sessions"),
// which the simulated Nano (app/src/sim/nano-programs.test.ts) must give too.
#include <gtest/gtest.h>

#include <string>

#include "printhead.h"
#include "vectors_fixture.h"

using namespace nano;
using namespace uvtest;

namespace {

const json V = loadVectors("nano-program.json");
VectorCounter counted("nano-program.json (sessions)");

// The board: a started chain is kept, and "run" plays it out as the timer would.
struct Board : PrintheadIo {
  uint8_t lit = 0;
  ScanStore* chain = nullptr;
  std::string out;
  void fire(const FirePlan& p) override { lit = p.onMask; }
  void allOff() override {
    lit = 0;
    chain = nullptr;
  }
  uint8_t litMask() const override { return lit; }
  uint32_t clockLineUs() override { return 0; }
  bool cut = false;  // the LEDs were cut, `cutTicks` after the on-edge or the chain's last event
  int32_t cutTicks = 0;
  bool takeCut(int32_t& t) override {
    t = cutTicks;
    bool was = cut;
    cut = false;
    return was;
  }
  bool startProgram(ScanStore& s) override {
    chain = &s;
    return true;
  }
  void servoPulse(uint16_t) override {}
  bool probeTriggered() override { return false; }
  void reply(const char* t, uint8_t n) override { out.append(t, n); }
  void linkSpeed(uint32_t, bool) override {}
  void run() {
    uint32_t d;
    uint8_t m;
    while (chain && chain->next(d, m) == ScanStore::Step::Event) lit = m;
    lit = 0;
    chain = nullptr;
  }
};

}  // namespace

TEST(ProgramSessions, ThePrintheadAnswersEverySession) {
  const PrintheadConfig config = {V["capUs"].get<uint32_t>(), {{600, 600, 600, 600, 600, 600}, 50, 100, 1750}, "0.2.0"};
  for (const json& c : V["sessions"]) {
    Board board;
    Printhead head(board, config);
    uint16_t mv[6] = {750, 750, 750, 750, 750, 750};
    head.readings(mv);
    for (const json& step : c["steps"]) {
      if (step.contains("run")) {
        board.run();
        continue;
      }
      std::string line = step["send"];
      board.out.clear();
      head.line(line.data(), static_cast<uint8_t>(line.size()), false, 0);
      std::string want = step.contains("reply") ? step["reply"].get<std::string>() + "\n" : "";
      EXPECT_EQ(board.out, want) << c["name"] << ": " << line;
    }
    counted();
  }
}
