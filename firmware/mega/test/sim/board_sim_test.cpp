// The real Mega image driving the real Nano image in simavr: the AVR glue (host UART interrupts,
// the step timer, the endstop pins, the Nano's UART) doing what the host tests prove of the logic,
// and the never-blocks figures measured on the compiled firmware.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <regex>

#include "board_fixture.h"
#include "printhead_link.h"

TEST_F(BoardTest, IdentifiesItselfAndReadsTheRealNanosTemperatures) {
  std::vector<std::string> info = cmd("M115");
  EXPECT_TRUE(said(info, "FIRMWARE_NAME:UVExposure 0.1.0 (Mega) PROTOCOL_VERSION:1"));
  EXPECT_TRUE(said(info, "Cap:RX_WINDOW:3"));
  EXPECT_TRUE(said(info, "Cap:SDCARD:0"));  // this build has no SdFat: no card
  sim.runUs(600000);
  std::vector<std::string> t = cmd("M105");
  // 750 mV on every sensor: 25.0 °C, or 24.7 through simavr's ADC, which scales by 1023 (nano_sim_test).
  EXPECT_TRUE(said(t, "T:24.7 /0.0 S0:24.7 /0.0 S1:24.7 /0.0 S2:24.7 /0.0 S3:24.7 /0.0 S4:24.7 /0.0 S5:24.7 /0.0"))
      << (t.empty() ? "" : t[0]);
  ASSERT_GE(sim.nanoLines.size(), 3u);
  // A board that raises the link first sends a 0x00 and, 2 ms later, its newline: they take a Nano
  // still at a raised speed back to 115200 (protocol/nano.md "Link speed"). Then the LEDs are off
  // before anything else is said.
  const size_t first = mega::kRaiseNanoLink ? 1 : 0;
  if (mega::kRaiseNanoLink) {
    EXPECT_EQ(sim.nanoLines[0], std::string(1, '\0'));
  }
  EXPECT_EQ(sim.nanoLines[first], "R");
  EXPECT_EQ(sim.nanoLines[first + 1], "V");
}

TEST_F(BoardTest, HomesOnTheSwitchesAndStepsExactlyWhereItIsSent) {
  std::vector<std::string> home = cmd("G28", 8e6);
  ASSERT_TRUE(said(home, "ok")) << home.back();
  EXPECT_EQ(sim.pos[0], -160);
  EXPECT_EQ(sim.pos[1], -80);
  EXPECT_EQ(sim.pos[2], -200);
  EXPECT_TRUE(said(cmd("M114"), "X:0.000 Y:0.000 Z:0.000 E:0.000 Count X:0 Y:0 Z:0"));
  cmd("G1 X2 Y1 Z0.5");
  sim.runUs(400000);
  EXPECT_EQ(sim.pos[0], -160 + 160);
  EXPECT_EQ(sim.pos[1], -80 + 80);
  EXPECT_EQ(sim.pos[2], -200 + 200);
  EXPECT_TRUE(said(cmd("M114"), "X:2.000 Y:1.000 Z:0.500 E:0.000 Count X:160 Y:80 Z:200"));
}

TEST_F(BoardTest, NeverBlocksTheLoopOrStarvesTheStepsWhileMovingAndTalking) {
  ASSERT_TRUE(said(cmd("G28", 8e6), "ok"));
  cmd("M155 S1");
  cmd("M821 R");
  sim.megaMaxInterruptsOff = 0;
  cmd("G1 X40 Y30");
  for (int i = 0; i < 6; i++) cmd("M105");  // both UARTs busy while the axes move
  sim.runUs(600000);
  std::vector<std::string> d = cmd("M821");
  std::smatch m;
  std::string line;
  for (const std::string& l : d)
    if (l.rfind("echo:DIAG", 0) == 0) line = l;
  ASSERT_TRUE(std::regex_search(line, m, std::regex(R"(loop_max_us=(\d+) step_isr_max_us=(\d+) underruns=(\d+) rx_dropped=(\d+))"))) << line;
  unsigned loopMax = std::stoul(m[1]), isrMax = std::stoul(m[2]);
  std::printf("[mega budget] longest main-loop pass while moving and reporting: %u us (queued segments cover 40000 us)\n", loopMax);
  std::printf("[mega budget] longest step interrupt, its latency included: %u us (the shortest step period is 62.5 us)\n", isrMax);
  std::printf("[mega budget] longest interrupts-off stretch: %.1f us (a byte at 115200 takes 86.8 us; the USART holds 2)\n",
              sim.megaMaxInterruptsOff / BoardSim::kCyclesPerUs);
  EXPECT_LT(loopMax, 20000u);  // half of what the queued segments cover
  EXPECT_LT(isrMax, 62u);
  EXPECT_LT(sim.megaMaxInterruptsOff / BoardSim::kCyclesPerUs, 86.8);
  EXPECT_EQ(m[3], "0");
  EXPECT_EQ(m[4], "0");
  EXPECT_EQ(sim.pos[0], -160 + 3200);
  EXPECT_EQ(sim.pos[1], -80 + 2400);
}

TEST_F(BoardTest, M112TellsTheNanoROnTheSpotAndHalts) {
  size_t before = sim.nanoLines.size();
  std::vector<std::string> r = cmd("M112");
  bool sentR = false;
  for (size_t i = before; i < sim.nanoLines.size(); i++) sentR |= sim.nanoLines[i] == "R";
  EXPECT_TRUE(sentR);
  EXPECT_TRUE(said(cmd("G28"), "Error:E13"));
  cmd("M999");
  EXPECT_TRUE(said(cmd("G1 X1"), "echo:E14"));
}
