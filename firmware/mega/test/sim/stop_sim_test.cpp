// One machine's stop cycle three ways: the real Mega and Nano images in simavr, the host rig the
// simulated printer is built on (mega_rig.h, compiled to WebAssembly for the app), and the planner's
// time model the app and the Mega estimate jobs with (protocol/planner.md "Time model"). Each stop
// of a stop-and-fire job is timed from its light's start to the next stop's. It prints the three
// figures (docs/firmware-mega.md "Stop cycle"); STOP_DEBUG=1 prints one stop's timeline each way.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "board_fixture.h"
#include "job_fixture.h"
#include "job_plan.h"
#include "printhead_link.h"
#include "mega_rig.h"
#include "time_model.h"

namespace {

using namespace mega::jobs;

// A job's stops, a 16 × 6 pattern at 2 ms, serpentine: short hops between stops, as a board's are.
struct StopJob {
  uv::JobHeader h = header(16, 6, uv::Strategy::Serpentine);
  Grid g = pattern(16, 6, 3);
  std::vector<uv::Stop> stops = plan(h, g);
};

// µs from the first stop's light to the last stop's, as the time model prices it: the whole job
// from the first stop's place, less that stop's overhead (it has no move) and the last stop's light.
double modelUs(const StopJob& j, const mega::Config& config) {
  uv::MotionModel m = mega::plannerMachine(config, 0, 0, mega::kJobLinkBaud);
  m.startUm[0] = static_cast<int32_t>(j.h.originUm[0]) + j.stops.front().hx * static_cast<int32_t>(j.h.pitchUm[0]);
  m.startUm[1] = static_cast<int32_t>(j.h.originUm[1]) + j.stops.front().hy * static_cast<int32_t>(j.h.pitchUm[1]);
  uv::PlanClock clock(j.h, m);
  for (const uv::Stop& s : j.stops) clock.add(s);
  const uv::Stop& last = j.stops.back();
  return static_cast<double>(clock.totalUs()) - m.overheadUs - *std::max_element(last.us, last.us + 4);
}

// How far the simulated printer and the time model may be from the real images, a part.
constexpr double kTolerance = 0.03;

class StopCycleTest : public BoardTest {};

}  // namespace

TEST_F(StopCycleTest, TheSimulatedPrinterAndTheTimeModelKeepTheRealImagesStopCycle) {
  const StopJob j;
  ASSERT_GT(j.stops.size(), 20u);

  // The real images: each stop's light begins where an LED goes on after all four were off.
  ASSERT_TRUE(said(cmd("G28", 8e6), "ok"));
  sim.logging = true;
  ASSERT_TRUE(said(numbered("M828"), "ok"));
  for (const std::string& r : encode(j.h, j.g)) ASSERT_TRUE(said(numbered(r), "ok")) << r;
  ASSERT_TRUE(said(numbered("M29"), "ok"));
  ASSERT_TRUE(sim.runUntil([&] {
    for (std::string& l : sim.takeLines()) seen.push_back(l);
    return said(seen, "JOB:done");
  }, 20e6));
  std::vector<double> real;
  int lit = 0;
  for (const BoardSim::LedEdge& e : sim.ledEdges) {
    if (e.on && lit == 0) real.push_back(static_cast<double>(e.cycle) / BoardSim::kCyclesPerUs);
    lit += e.on ? 1 : -1;
  }
  ASSERT_EQ(real.size(), j.stops.size());
  if (getenv("STOP_DEBUG")) {  // one stop's timeline, µs from its light: LEDs, the link, the moves' ends
    const double from = real[3], to = real[5];
    std::vector<std::pair<double, std::string>> t;
    for (const BoardSim::LedEdge& e : sim.ledEdges) t.push_back({e.cycle / BoardSim::kCyclesPerUs, "LED " + std::to_string(e.led) + (e.on ? " on" : " off")});
    for (const BoardSim::LinkLine& l : sim.linkLines) t.push_back({l.cycle / BoardSim::kCyclesPerUs, (l.toNano ? "  > " : "  < ") + l.text});
    for (size_t i = 0; i < sim.headSteps.size(); i++) {
      const bool first = i == 0 || sim.headSteps[i].cycle - sim.headSteps[i - 1].cycle > 2000 * 16;
      const bool last = i + 1 == sim.headSteps.size() || sim.headSteps[i + 1].cycle - sim.headSteps[i].cycle > 2000 * 16;
      if (first || last) t.push_back({sim.headSteps[i].cycle / BoardSim::kCyclesPerUs, first ? "move's first step" : "move's last step"});
    }
    std::sort(t.begin(), t.end());
    for (const auto& e : t)
      if (e.first >= from && e.first <= to) std::printf("%8.0f  %s\n", e.first - from, e.second.c_str());
  }

  // The rig, on the same job.
  mega::MegaRig rig;
  rig.sd.inserted = false;
  rig.nano.logging = true;
  rig.begin();
  rig.run(600000);
  ASSERT_EQ(rig.cmd("G28").back().rfind("ok", 0), 0u);
  rig.cmd("M828");
  for (const std::string& r : encode(j.h, j.g)) rig.cmd(r);
  rig.cmd("M29");
  // STOP_DEBUG: the rig's timeline in its 100 µs passes, from its fourth stop's light to its sixth's.
  std::vector<std::pair<uint64_t, std::string>> rigT;
  int32_t was[3] = {0, 0, 0};
  bool moving = false;
  for (uint64_t t = 0; t < 20000000 && !said(rig.usbLines, "JOB:done"); t += 100) {
    const size_t lines = rig.nano.lines.size();
    const uint8_t lit = rig.nano.lit();
    rig.run(100);
    if (!getenv("STOP_DEBUG")) continue;
    for (size_t i = lines; i < rig.nano.lines.size(); i++) rigT.push_back({rig.nowUs, "  > " + rig.nano.lines[i]});
    if (lit != rig.nano.lit()) rigT.push_back({rig.nowUs, "LEDs " + std::to_string(rig.nano.lit())});
    int32_t p[3];
    rig.rig.motion.positionSteps(p);
    const bool moved = p[0] != was[0] || p[1] != was[1] || p[2] != was[2];
    if (moved != moving) rigT.push_back({rig.nowUs, moved ? "moving" : "still"});
    moving = moved;
    std::copy(p, p + 3, was);
  }
  if (getenv("STOP_DEBUG") && rig.nano.exposures.size() > 5) {
    const uint64_t from = rig.nano.exposures[3].startUs, to = rig.nano.exposures[5].startUs + 100;
    std::printf("the rig:\n");
    for (const auto& e : rigT)
      if (e.first >= from && e.first <= to) std::printf("%8llu  %s\n", static_cast<unsigned long long>(e.first - from), e.second.c_str());
  }
  ASSERT_TRUE(said(rig.usbLines, "JOB:done"));
  ASSERT_EQ(rig.nano.exposures.size(), j.stops.size());

  const double realUs = real.back() - real.front();
  const double rigUs = static_cast<double>(rig.nano.exposures.back().startUs - rig.nano.exposures.front().startUs);
  const double model = modelUs(j, rig.config);
  const double n = static_cast<double>(j.stops.size() - 1);
  std::printf("[stop cycle] %zu stops of a 16 x 6 serpentine job at 2 ms: the real images %.0f us a stop, the simulated printer's rig %.0f us "
              "(%+.2f %%), the time model %.0f us (%+.2f %%; stop_overhead_us %u)\n",
              j.stops.size(), realUs / n, rigUs / n, (rigUs / realUs - 1) * 100, model / n, (model / realUs - 1) * 100,
              static_cast<unsigned>(rig.config.whole(mega::Key::StopOverheadUs)));
  // Within 3 %: the rig and the model count the wire and the polls, not the Mega's CPU time.
  EXPECT_NEAR(rigUs / realUs, 1.0, kTolerance);
  EXPECT_NEAR(model / realUs, 1.0, kTolerance);
}
