// The command core as Marlin hosts (OctoPrint, Pronterface) see it: refusals as echo:, faults as Error:,
// G4, M400, G28 and M18/M84 after the queued moves, the modal feed rate, M117 alone, the busy: interval
// (M113), M108 and M21 (protocol/mega.md §5a).
#include "machine.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "mega_rig.h"

using namespace mega;

namespace {

using Lines = std::vector<std::string>;

class MarlinHostTest : public ::testing::Test {
 protected:
  MegaRig m;
  void SetUp() override { m.begin(); }
  Lines payload(const std::string& body, bool esp = false) { return MegaRig::payload(m.cmd(body, esp)); }
  // Microseconds a command takes from its send to its ok.
  uint64_t timed(const std::string& body) {
    uint64_t start = m.nowUs;
    m.cmd(body);
    return m.nowUs - start;
  }
  long count(const std::string& prefix, size_t from) {
    return std::count_if(m.usbLines.begin() + static_cast<long>(from), m.usbLines.end(),
                         [&](const std::string& l) { return l.rfind(prefix, 0) == 0; });
  }
};

}  // namespace

TEST_F(MarlinHostTest, RefusalsAreEchoedAndLeaveTheMachineAsItWas) {
  // A cancelled print's script sends M84: the next jog is refused, not an error that ends the connection.
  EXPECT_EQ(payload("G1 X10"), (Lines{"echo:E14 axis not homed: X"}));
  EXPECT_EQ(payload("M104 S0"), (Lines{"echo:E10 unknown command: M104"}));
  m.cmd("G28");
  EXPECT_EQ(payload("G1 X9999"), (Lines{"echo:E15 target outside soft limits: X"}));
  EXPECT_EQ(payload("M114"), (Lines{"X:0.000 Y:0.000 Z:0.000 E:0.000 Count X:0 Y:0 Z:0"}));
  m.cmd("M84");
  EXPECT_EQ(payload("G1 X10"), (Lines{"echo:E14 axis not homed: X"}));
}

TEST_F(MarlinHostTest, FaultsKeepError) {
  m.rig.switchAt[1] = INT32_MIN;
  EXPECT_EQ(payload("G28 Y"), (Lines{"Error:E44 endstop not found while homing: Y"}));
  m.send("M112");
  m.run(100000);
  EXPECT_EQ(payload("M105"), (Lines{"Error:E13 machine halted: send M999"}));
}

TEST_F(MarlinHostTest, M400AnswersWhenTheLastMoveHasEnded) {
  m.cmd("G28");
  m.cmd("G1 X100 Y50 F3000");  // queued at once: its ok comes before the move ends
  EXPECT_NE(payload("M114"), (Lines{"X:100.000 Y:50.000 Z:0.000 E:0.000 Count X:8000 Y:4000 Z:0"}));
  EXPECT_GT(timed("M400"), 1000000u);  // about 2 s at 50 mm/s
  EXPECT_EQ(payload("M114"), (Lines{"X:100.000 Y:50.000 Z:0.000 E:0.000 Count X:8000 Y:4000 Z:0"}));
  EXPECT_LT(timed("M400"), 50000u);  // nothing queued: at once
}

TEST_F(MarlinHostTest, G4WaitsForTheMovesBeforeItThenDwells) {
  m.cmd("G28");
  m.cmd("G1 X100 F6000");
  uint64_t dwell = timed("G4 P100");
  m.cmd("G1 X0 F6000");
  uint64_t move = timed("M400");
  EXPECT_GE(dwell, move + 100000 - 5000);  // the same move's time, and then the dwell
  EXPECT_LT(timed("G4 P100"), 150000u);
  EXPECT_EQ(payload("G4 S4294.968"), (Lines{"echo:E11 bad or missing parameter: S"}));
}

TEST_F(MarlinHostTest, G28FinishesTheMovesQueuedBeforeIt) {
  m.cmd("G28");
  m.cmd("G1 X150 F6000");
  m.cmd("G28 Y");
  EXPECT_EQ(payload("M114"), (Lines{"X:150.000 Y:0.000 Z:0.000 E:0.000 Count X:12000 Y:0 Z:0"}));
}

TEST_F(MarlinHostTest, M113SetsThisPortsBusyIntervalAndZeroSendsNone) {
  EXPECT_EQ(payload("M113"), (Lines{"echo:M113 S2"}));
  m.cmd("M113 S5");
  EXPECT_EQ(payload("M113"), (Lines{"echo:M113 S5"}));
  EXPECT_EQ(payload("M113", true), (Lines{"echo:M113 S2"}));  // the other port keeps its own
  size_t from = m.usbLines.size();
  m.cmd("G4 S11");
  EXPECT_EQ(count("busy:", from), 2);  // at 5 s and 10 s
  m.cmd("M113 S0");
  from = m.usbLines.size();
  m.cmd("G4 S5");
  EXPECT_EQ(count("busy:", from), 0);
  EXPECT_EQ(payload("M113 S61"), (Lines{"echo:E11 bad or missing parameter: S"}));
  EXPECT_EQ(payload("M113 S1.5"), (Lines{"echo:E11 bad or missing parameter: S"}));
}

TEST_F(MarlinHostTest, M108IsAcceptedAndM21SaysWhetherTheCardIsThere) {
  EXPECT_EQ(payload("M108"), Lines{});
  EXPECT_EQ(payload("M21"), (Lines{"echo:SD card ok"}));
}

TEST_F(MarlinHostTest, TheFeedRateIsModalUntilTheNextF) {
  m.cmd("G28");
  m.cmd("G1 X40 Y30 F600");  // 10 mm/s: 50 mm along the diagonal, X's 40 mm set the time
  EXPECT_GT(timed("M400"), 3900000u);
  m.cmd("G1 X70 Y30");  // no F: still 10 mm/s, 3 s (at travel speed it would be about 0.4 s)
  uint64_t kept = timed("M400");
  EXPECT_GT(kept, 2900000u);
  EXPECT_LT(kept, 3200000u);
  m.cmd("G0 X40");  // G0 shares G1's feed rate, as in Marlin
  EXPECT_GT(timed("M400"), 2900000u);
  m.cmd("G1 F6000");  // F alone on its line is kept too: 100 mm/s
  m.cmd("G1 X70");
  EXPECT_LT(timed("M400"), 1000000u);
  EXPECT_EQ(payload("M114"), (Lines{"X:70.000 Y:30.000 Z:0.000 E:0.000 Count X:5600 Y:2400 Z:0"}));
}

TEST_F(MarlinHostTest, ARefusedMoveKeepsTheFeedRateItHad) {
  m.cmd("G28");
  m.cmd("G1 X10 F600");
  EXPECT_EQ(payload("G1 X9999 F6000"), (Lines{"echo:E15 target outside soft limits: X"}));
  EXPECT_EQ(payload("G1 X20 F0"), (Lines{"echo:E11 bad or missing parameter: F"}));
  m.cmd("M400");
  m.cmd("G1 X40");  // still 10 mm/s
  EXPECT_GT(timed("M400"), 2900000u);
}

TEST_F(MarlinHostTest, AfterM112AndM999TheFeedRateIsTheConfiguredSpeedAgain) {
  m.cmd("G28");
  m.cmd("G1 X10 F60");  // 1 mm/s
  m.send("M112");
  m.run(100000);
  m.cmd("M999");
  m.cmd("G28");
  m.cmd("G1 X50");  // at travel speed (100 mm/s), as after Marlin's reset
  EXPECT_LT(timed("M400"), 1500000u);
}

TEST_F(MarlinHostTest, M84FinishesTheQueuedMovesBeforeItReleasesTheMotors) {
  for (const char* release : {"M84", "M18"}) {
    m.cmd("G28");
    m.cmd("G1 X150 Y150 F6000");
    m.cmd(release);
    m.cmd("M400");
    EXPECT_EQ(payload("M114"), (Lines{"X:150.000 Y:150.000 Z:0.000 E:0.000 Count X:12000 Y:12000 Z:0"})) << release;
    EXPECT_EQ(payload("G1 X10"), (Lines{"echo:E14 axis not homed: X"})) << release;
  }
}

TEST_F(MarlinHostTest, M117AloneClearsTheMessage) {
  EXPECT_EQ(payload("M117 UVP-1A2B"), Lines{});
  m.run(300000);
  EXPECT_EQ(m.display.rows[7], "UVP-1A2B        ");
  EXPECT_EQ(payload("M117"), Lines{});
  m.run(300000);
  EXPECT_EQ(m.display.rows[7], "                ");
  EXPECT_EQ(payload("M850"), (Lines{"echo:E11 bad or missing parameter"}));  // M850 still needs its key
}
