// The command core, driven the way hosts drive it: numbered lines in, reply blocks out, with the
// motion, the printhead (the real Nano logic), the SD card and the EEPROM behind it.
#include "machine.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "mega_rig.h"

using namespace mega;

namespace {

using Lines = std::vector<std::string>;

bool has(const Lines& lines, const std::string& prefix) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(prefix, 0) == 0; });
}

class MachineTest : public ::testing::Test {
 protected:
  MegaRig m;
  void SetUp() override { m.begin(); }
  Lines payload(const std::string& body, bool esp = false) { return MegaRig::payload(m.cmd(body, esp)); }
};

}  // namespace

TEST_F(MachineTest, StartsOnBothPortsAndM115ListsTheCapabilities) {
  EXPECT_EQ(m.usbLines.front(), "start");
  EXPECT_EQ(m.espLines.front(), "start");
  Lines p = payload("M115");
  EXPECT_EQ(p, (Lines{"FIRMWARE_NAME:UVExposure 0.1.0 (Mega) PROTOCOL_VERSION:1 MACHINE_TYPE:UV-LED exposure printer LEDS:4 SENSORS:6",
                      "Cap:RX_WINDOW:3", "Cap:AUTOREPORT_TEMP:1", "Cap:AUTOREPORT_POS:1", "Cap:SDCARD:1", "Cap:RESUME:1",
                      "Cap:JOB_FORMAT:2", "Cap:LINK_BAUD:250000"}));
  Lines block = m.cmd("M115");
  EXPECT_EQ(block.back().rfind("ok N2 P8 B3*", 0), 0u);
  // The ESP's port has a window of its own, smaller: its sender is on a wire (line_ring.h).
  Lines esp = payload("M115", true);
  EXPECT_NE(std::find(esp.begin(), esp.end(), "Cap:RX_WINDOW:2"), esp.end());
  EXPECT_EQ(m.cmd("M115", true).back().rfind("ok N2 P8 B2*", 0), 0u);
}

TEST_F(MachineTest, UnknownCommandsAndBadParametersAreRefusedWithTheirCodes) {
  EXPECT_EQ(payload("M9876"), (Lines{"echo:E10 unknown command: M9876"}));
  EXPECT_EQ(payload("G1 X"), (Lines{"echo:E11 bad or missing parameter: X"}));
  EXPECT_EQ(payload("M155 S61"), (Lines{"echo:E11 bad or missing parameter"}));
}

TEST_F(MachineTest, M105ReportsEverySensorWithoutATargetAndM155RepeatsIt) {
  m.run(600000);
  Lines p = payload("M105");
  ASSERT_EQ(p.size(), 0u);  // T: lines are filtered as reports: look at the raw block
  Lines block = m.cmd("M105");
  EXPECT_EQ(block[0], "T:25.0 /0.0 S0:25.0 /0.0 S1:25.0 /0.0 S2:25.0 /0.0 S3:25.0 /0.0 S4:25.0 /0.0 S5:25.0 /0.0");
  // No host may show a soft limit as a heater's target: a host that wants them reads the config.
  EXPECT_EQ(payload("M850 thermal.limit.4"), (Lines{"M850 thermal.limit.4 50"}));
  m.cmd("M155 S1");
  size_t before = m.espLines.size();
  m.run(3100000);  // the third report needs its 8 ms on the wire
  long reports = std::count_if(m.espLines.begin() + static_cast<long>(before), m.espLines.end(), [](const std::string& l) { return l.rfind("T:", 0) == 0; });
  EXPECT_EQ(reports, 3);  // both ports get the auto-report
  m.nano.silent = true;
  m.run(1000000);
  EXPECT_TRUE(has(m.usbLines, "FAULT:E30 printhead not responding"));
  EXPECT_EQ(payload("M105"), (Lines{"Error:E30 printhead not responding"}));
}

TEST_F(MachineTest, G28HomesEveryAxisToZeroAndMovesThenGoWhereAsked) {
  EXPECT_EQ(payload("G1 X10"), (Lines{"echo:E14 axis not homed: X"}));
  Lines home = m.cmd("G28");
  EXPECT_EQ(home.back().rfind("ok N2 ", 0), 0u);
  EXPECT_EQ(payload("M114"), (Lines{"X:0.000 Y:0.000 Z:0.000 E:0.000 Count X:0 Y:0 Z:0"}));
  EXPECT_TRUE(m.io.enabled);
  m.cmd("G1 X10 Y20.5 Z1");
  m.run(2000000);
  EXPECT_EQ(payload("M114"), (Lines{"X:10.000 Y:20.500 Z:1.000 E:0.000 Count X:800 Y:1640 Z:400"}));
  m.cmd("G91");
  m.cmd("G1 X-2.5 F600");
  m.cmd("G90");
  m.run(2000000);
  EXPECT_EQ(payload("M114"), (Lines{"X:7.500 Y:20.500 Z:1.000 E:0.000 Count X:600 Y:1640 Z:400"}));
  EXPECT_EQ(payload("G1 X200.001"), (Lines{"echo:E15 target outside soft limits: X"}));
  EXPECT_EQ(payload("G1 Y-1"), (Lines{"echo:E15 target outside soft limits: Y"}));
}

TEST_F(MachineTest, AHomingThatFindsNoSwitchFailsWithE44) {
  m.rig.switchAt[1] = INT32_MIN;
  EXPECT_EQ(payload("G28 Y"), (Lines{"Error:E44 endstop not found while homing: Y"}));
  EXPECT_EQ(payload("G1 Y5"), (Lines{"echo:E14 axis not homed: Y"}));
}

TEST_F(MachineTest, ALongCommandSendsBusyAndTheOtherPortsQueriesStillRun) {
  m.rig.switchAt[0] = -80 * 150;  // 150 mm away: a few seconds of homing
  m.send("G28 X");
  m.run(1000);
  Lines esp = m.cmd("M114", true);
  EXPECT_TRUE(has(esp, "X:"));
  EXPECT_FALSE(has(m.usbLines, "ok N1"));  // still homing
  m.run(6000000);
  EXPECT_TRUE(has(m.usbLines, "busy: processing"));
  EXPECT_TRUE(has(m.usbLines, "ok N1 "));
}

TEST_F(MachineTest, AJogRunsUntilM410AndStopsInsideTheBed) {
  m.cmd("G28");
  m.cmd("M820 X1 S1");
  m.run(500000);
  m.cmd("M410");
  m.run(500000);
  Lines p = payload("M114");
  int32_t steps[3];
  m.rig.motion.positionSteps(steps);
  EXPECT_GT(steps[0], 80 * 5);
  EXPECT_LT(steps[0], 80 * 40);
  m.run(500000);
  int32_t later[3];
  m.rig.motion.positionSteps(later);
  EXPECT_EQ(later[0], steps[0]);  // stopped
  EXPECT_EQ(payload("M820 X2"), (Lines{"echo:E11 bad or missing parameter"}));
  // Unstopped, a jog ends at the soft limit.
  m.cmd("M820 Y1 S1");
  m.run(8000000);
  m.rig.motion.positionSteps(later);
  EXPECT_EQ(later[1], 200 * 80);
}

TEST_F(MachineTest, TheSelfTestReportsEachAxis) {
  EXPECT_EQ(payload("M822 Q"), (Lines{"echo:E14 axis not homed: home first (G28)"}));
  m.cmd("G28");  // the head stays on the switches, its count 0 there
  EXPECT_EQ(payload("M822 Q"), (Lines{"TEST:quick x=pass x_steps=1600 y=pass y_steps=1600"}));
  EXPECT_EQ(payload("M822"), (Lines{"TEST:full x=pass x_steps=16000 y=pass y_steps=16000"}));
}

TEST_F(MachineTest, TheProbeServoAndItsAlarm) {
  m.run(600000);
  EXPECT_EQ(payload("M401"), (Lines{"PROBE:deployed"}));
  EXPECT_EQ(m.nano.servoUs, 647);
  EXPECT_EQ(payload("M402"), (Lines{"PROBE:stowed"}));
  EXPECT_EQ(m.nano.servoUs, 1473);
  EXPECT_EQ(payload("M280 P0 S160"), (Lines{"PROBE:stowed"}));
  EXPECT_EQ(m.nano.servoUs, 2194);
  EXPECT_EQ(payload("M280 P0 S45"), (Lines{"echo:E11 bad or missing parameter"}));
  m.nano.probe = true;  // deployed but the signal is high: the CR Touch's alarm
  EXPECT_EQ(payload("M401"), (Lines{"PROBE:alarm", "Error:E40 probe alarm"}));
}

TEST_F(MachineTest, M119ReadsTheSwitchesAndTheProbe) {
  m.run(600000);
  m.rig.switchAt[1] = 10;  // Y closed now
  EXPECT_EQ(payload("M119"), (Lines{"x_min: open", "y_min: TRIGGERED", "z_min: open", "z_probe: open"}));
}

TEST_F(MachineTest, ConfigIsSetQueriedSavedLoadedAndReported) {
  EXPECT_EQ(payload("M850 accel.x"), (Lines{"M850 accel.x 2000"}));
  EXPECT_EQ(payload("M850 accel.x 2500"), Lines{});
  EXPECT_EQ(payload("M850 accel.x"), (Lines{"M850 accel.x 2500"}));
  EXPECT_EQ(payload("M850 accel.x fast"), (Lines{"echo:E50 config value invalid: accel.x fast"}));
  EXPECT_EQ(payload("M850 nozzle 3"), (Lines{"echo:E50 config value invalid: nozzle 3"}));
  EXPECT_EQ(payload("M500"), (Lines{"echo:Settings stored"}));
  EXPECT_NE(m.sd.contents("CONFIG.TXT").find("accel.x = 2500\n"), std::string::npos);
  EXPECT_EQ(payload("M502"), Lines{});
  EXPECT_EQ(payload("M850 accel.x"), (Lines{"M850 accel.x 2000"}));
  EXPECT_EQ(payload("M501"), Lines{});
  EXPECT_EQ(payload("M850 accel.x"), (Lines{"M850 accel.x 2500"}));
  Lines report = payload("M503");
  ASSERT_EQ(report.size(), kKeyCount);
  EXPECT_EQ(report[0], "M850 steps_per_mm.x 80");
  EXPECT_EQ(report[11], "M850 accel.x 2500");
}

TEST_F(MachineTest, DirectionInversionActsAtOnce) {
  EXPECT_EQ(m.io.inverted, 0);
  m.cmd("M850 invert.y 1");
  EXPECT_EQ(m.io.inverted, 2);
  m.cmd("M850 invert.z 1");
  EXPECT_EQ(m.io.inverted, 6);
  m.cmd("M502");
  EXPECT_EQ(m.io.inverted, 0);
}

TEST_F(MachineTest, ChangingStepsPerMmMeansHomingAgain) {
  m.cmd("G28");
  m.cmd("M850 steps_per_mm.x 100");
  EXPECT_EQ(payload("G1 X1"), (Lines{"echo:E14 axis not homed: X"}));
  EXPECT_EQ(payload("G1 Y1"), Lines{});
}

TEST_F(MachineTest, M112HaltsAtOnceAndOnlyM999Releases) {
  m.cmd("G28");
  m.cmd("G1 X150");
  m.run(200000);
  size_t sent = m.nano.lines.size();
  m.send("M112");
  m.run(2500);  // its 24 bytes take 2.1 ms on the wire; it acts the moment its '\n' is in
  ASSERT_GT(m.nano.lines.size(), sent);
  EXPECT_EQ(m.nano.lines[sent], "R");
  int32_t at[3], later[3];
  m.rig.motion.positionSteps(at);
  m.run(500000);
  m.rig.motion.positionSteps(later);
  EXPECT_EQ(at[0], later[0]);
  EXPECT_FALSE(m.io.enabled);
  m.usbLines.clear();
  m.run(1000);
  EXPECT_EQ(payload("G28"), (Lines{"Error:E13 machine halted: send M999"}));
  EXPECT_EQ(payload("M999"), Lines{});
  EXPECT_EQ(payload("G1 X1"), (Lines{"echo:E14 axis not homed: X"}));  // steps may have been lost
}

TEST_F(MachineTest, DwellLightAndRelease) {
  Lines dwell = m.cmd("G4 P500");
  EXPECT_GE(m.nowUs, 500000u);
  m.cmd("M355 S1");
  EXPECT_TRUE(m.io.lightOn);
  EXPECT_EQ(m.io.lightPin, 57);
  m.cmd("M850 light.pin 8");
  EXPECT_EQ(payload("M355 S1"), (Lines{"echo:E11 bad or missing parameter: light.pin is not a free pin"}));
  m.cmd("G28");
  m.cmd("M18");
  EXPECT_FALSE(m.io.enabled);
  EXPECT_EQ(payload("G1 X1"), (Lines{"echo:E14 axis not homed: X"}));
}

TEST_F(MachineTest, LongDwellsWaitTheirTimeAndTooLongOnesAreRefused) {
  // 2148 s is 2^31 µs and more: it once ended at once, its end read as already past.
  uint32_t n = m.send("G4 S2148");
  m.run(3000000);
  std::string okPrefix = "ok N" + std::to_string(n) + " ";
  EXPECT_FALSE(std::any_of(m.usbLines.begin(), m.usbLines.end(), [&](const std::string& l) { return l.rfind(okPrefix, 0) == 0; }));
  EXPECT_TRUE(has(m.usbLines, "busy: processing"));
  m.cmd("M112", true);  // ends the dwell, answered halted
  m.run(10000);
  EXPECT_TRUE(has(m.usbLines, "Error:E13"));
  m.cmd("M999");
  EXPECT_EQ(payload("G4 S4295"), (Lines{"echo:E11 bad or missing parameter: S"}));  // past 2^32 µs
  uint64_t before = m.nowUs;
  m.cmd("G4 S1.5");
  EXPECT_GE(m.nowUs - before, 1500000u);
  EXPECT_LT(m.nowUs - before, 1510000u);
}

TEST_F(MachineTest, PositionAutoReportsMotorsOnAndOffAndJobStatusReports) {
  m.cmd("G28");
  m.cmd("M154 P100");  // every 100 ms
  size_t from = m.usbLines.size();
  m.run(1050000);
  long positions = std::count_if(m.usbLines.begin() + static_cast<long>(from), m.usbLines.end(), [](const std::string& l) { return l.rfind("X:", 0) == 0; });
  EXPECT_GE(positions, 9);
  EXPECT_LE(positions, 11);
  EXPECT_EQ(payload("M154 P20"), (Lines{"echo:E11 bad or missing parameter"}));  // 50 ms at the least
  m.cmd("M154 S0");
  from = m.usbLines.size();
  m.run(500000);
  EXPECT_EQ(std::count_if(m.usbLines.begin() + static_cast<long>(from), m.usbLines.end(), [](const std::string& l) { return l.rfind("X:", 0) == 0; }), 0);
  m.cmd("M84");
  EXPECT_FALSE(m.io.enabled);
  EXPECT_EQ(payload("G1 X1"), (Lines{"echo:E14 axis not homed: X"}));
  m.cmd("M17");
  EXPECT_TRUE(m.io.enabled);
  m.cmd("M27 S1");
  from = m.usbLines.size();
  m.run(2100000);
  EXPECT_EQ(std::count_if(m.usbLines.begin() + static_cast<long>(from), m.usbLines.end(), [](const std::string& l) { return l == "JOB:idle"; }), 2);
  EXPECT_EQ(payload("M1000 C"), Lines{});  // nothing to discard is no error
  EXPECT_EQ(payload("M1000"), (Lines{"echo:E27 no interrupted job to resume"}));
}
