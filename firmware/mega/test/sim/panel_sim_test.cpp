// The panel on the real Mega image in simavr: the SSD1306 model on the TWI reads back what the
// screen shows, and the rig measures what drawing it costs the main loop while the axes move.
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <set>

#include "board_fixture.h"
#include "job_fixture.h"

namespace {

class PanelTest : public BoardTest {
 protected:
  std::string row(int r) { return sim.panel.row(static_cast<uint8_t>(r)); }
  // Runs until row r reads `text` (the screen sweeps its rows every 24 ms); false after maxUs.
  bool shows(int r, const std::string& text, double maxUs = 300000) {
    return sim.runUntil([&] { return row(r) == text; }, maxUs);
  }
};

}  // namespace

TEST_F(PanelTest, ShowsStatePositionTemperaturesAndTheM117Message) {
  // A query sent as `start` arrives, while the panel is set up and its first screen drawn.
  uint64_t sent = sim.megaCycle();
  std::vector<std::string> info = cmd("M115");
  double m115Ms = (sim.megaCycle() - sent) / BoardSim::kCyclesPerUs / 1000;
  EXPECT_TRUE(said(info, "FIRMWARE_NAME:"));
  std::printf("[mega budget] panel: M115 sent at start, during the first screen fill: its ok after %.1f ms\n", m115Ms);
  EXPECT_LT(m115Ms, 50);
  EXPECT_TRUE(shows(0, "UV ready        ")) << row(0);
  EXPECT_TRUE(sim.panel.on());
  EXPECT_TRUE(sim.panel.chargePump());
  EXPECT_TRUE(sim.panel.upright());
  EXPECT_TRUE(shows(1, "not homed: G28  ")) << row(1);
  EXPECT_TRUE(shows(2, "Z  0.000        ")) << row(2);
  // The real Nano's temperatures once it has reported (24.7: simavr's ADC scales by 1023).
  EXPECT_TRUE(shows(5, "T0 24.7/55.0C   ", 1.5e6)) << row(5);
  ASSERT_TRUE(said(cmd("G28", 8e6), "ok"));
  EXPECT_TRUE(shows(1, "X   0.00Y   0.00")) << row(1);
  cmd("M117 UVP-1A2B ready");
  EXPECT_TRUE(shows(7, "UVP-1A2B ready  ")) << row(7);
  EXPECT_EQ(row(6), "                ");  // no fault
  EXPECT_EQ(row(3), "                ");  // no job
}

TEST_F(PanelTest, ShowsTheHottestSensorAndItsFaultAndTheHalt) {
  sim.setNanoMv(2, 1150);  // 65 °C on sensor 2, over its 55 °C limit
  EXPECT_TRUE(sim.runUntil([&] { return std::regex_match(row(5), std::regex(R"(T2 6\d\.\d/55\.0C   )")); }, 3e6)) << row(5);
  EXPECT_TRUE(shows(6, "fault E31       ", 1e6)) << row(6);  // 31: over-temperature
  cmd("M112");
  EXPECT_TRUE(shows(0, "UV HALTED M999  ")) << row(0);
}

TEST_F(PanelTest, RedrawsThePositionWhileMovingWithoutHoldingTheLoop) {
  ASSERT_TRUE(said(cmd("G28", 8e6), "ok"));
  EXPECT_TRUE(shows(1, "X   0.00Y   0.00")) << row(1);
  cmd("M821 R");
  sim.resetPanelFigures();
  uint32_t framesBefore = sim.panel.writes();
  uint64_t t0 = sim.megaCycle();
  cmd("G1 X40 Y30");
  std::set<std::string> positions;
  // Replies while the panel draws: how long a query waits for its ok.
  double replyMaxUs = 0;
  for (int i = 0; i < 6; i++) {
    uint64_t sent = sim.megaCycle();
    cmd("M105");
    replyMaxUs = std::max(replyMaxUs, (sim.megaCycle() - sent) / BoardSim::kCyclesPerUs);
    positions.insert(row(1));
  }
  sim.runUntil([&] {
    positions.insert(row(1));
    return row(1) == "X  40.00Y  30.00";
  }, 2e6);
  EXPECT_EQ(row(1), "X  40.00Y  30.00");
  EXPECT_GE(positions.size(), 4u);  // the head was shown on its way
  double seconds = (sim.megaCycle() - t0) / BoardSim::kCyclesPerUs / 1e6;
  std::vector<std::string> d = cmd("M821");
  std::smatch m;
  std::string line;
  for (const std::string& l : d)
    if (l.rfind("echo:DIAG", 0) == 0) line = l;
  ASSERT_TRUE(std::regex_search(line, m, std::regex(R"(loop_max_us=(\d+) .*underruns=(\d+))"))) << line;
  unsigned loopMax = std::stoul(m[1]);
  double passUs = sim.panelPassMax / BoardSim::kCyclesPerUs, isrUs = sim.twiIsrMax / BoardSim::kCyclesPerUs;
  uint32_t frames = sim.panel.writes() - framesBefore;
  std::printf("[mega budget] panel: longest main-loop pass while it redraws during motion: %u us (queued segments cover 40000 us)\n", loopMax);
  std::printf("[mega budget] panel: its CPU per main-loop pass, at most %.0f us over %llu passes (budget 1000 us): the screen at most %.0f us, "
              "the TWI interrupt %.1f us a byte\n",
              passUs, static_cast<unsigned long long>(sim.panelPasses), sim.panelCallMax / BoardSim::kCyclesPerUs, isrUs);
  std::printf("[mega budget] panel: %u frames in %.2f s of motion; M105 answered within %.1f ms while it drew\n", frames, seconds,
              replyMaxUs / 1000);
  ASSERT_GT(sim.panelPasses, 100u);  // the rig found Machine::panel() in the image
  EXPECT_LT(passUs, 1000);
  EXPECT_LT(isrUs, 20);
  EXPECT_LT(loopMax, 20000u);
  EXPECT_EQ(m[2], "0");  // no step underruns
  EXPECT_GT(frames, 9u * 4);  // the position row went out whole several times
  EXPECT_LT(replyMaxUs, 20000);
}

TEST_F(PanelTest, ShowsAStreamedJobsProgressAndItsEnd) {
  using namespace mega::jobs;
  ASSERT_TRUE(said(cmd("G28", 8e6), "ok"));
  uv::JobHeader h = header(10, 4, uv::Strategy::Raster);
  Grid g = pattern(10, 4, 7);
  size_t stops = plan(h, g).size();
  ASSERT_GT(stops, 3u);
  ASSERT_TRUE(said(numbered("M828"), "ok"));
  for (const std::string& r : encode(h, g)) ASSERT_TRUE(said(numbered(r), "ok")) << r;
  ASSERT_TRUE(said(numbered("M29"), "ok"));
  std::regex progress(R"(stop (\d+)/(\d+) *)");
  std::smatch m;
  std::string during;
  EXPECT_TRUE(sim.runUntil([&] {
    std::string r3 = row(3);
    if (row(0) == "UV EXPOSING     " && std::regex_match(r3, m, progress) && m[1] != "0") during = r3;
    return !during.empty();
  }, 10e6)) << row(0) << "|" << row(3);
  std::string end = "stop " + std::to_string(stops) + "/" + std::to_string(stops);
  end.resize(16, ' ');
  EXPECT_TRUE(shows(3, end, 20e6)) << row(3);
  EXPECT_TRUE(shows(0, "UV job done     ")) << row(0);
}
