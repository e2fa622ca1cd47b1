// A scan job's passes run by ScanRun through the real printhead link and the real Nano logic
// (FakeNano), with the step interrupt's code moving the head in simulated time: the G goes out on
// its step and reaches the Nano two byte-times later, and every cell's dose and every LED edge is
// measured from the light's times and the head's steps (scan_dose.h).
#include <gtest/gtest.h>

#include <cstdio>

#include "fake_nano.h"
#include "grid_cells.h"
#include "job_fixture.h"
#include "motion_rig.h"
#include "printhead_link.h"
#include "scan_dose.h"
#include "scan_run.h"

using namespace mega;

namespace {

constexpr uint64_t kLoopTicks = 1000;  // the main loop every 500 µs
constexpr uint64_t kGTicks = 2 * 170;  // "G\n" on the wire

struct ScanRunTest : ::testing::Test {
  Config config;  // 80 steps/mm, 100 mm/s, 2000 mm/s²
  MotionRig rig{config};
  FakeNano nano;
  PrintheadLink link{nano};
  uint64_t gAt = 0;

  // The machine tests' job at 50 µm, every LED at the same gain, the LEDs spread in X too.
  uv::JobHeader job(uint16_t cols, uint16_t rows, uint32_t fullUs) {
    uv::JobHeader h = jobs::header(cols, rows, uv::Strategy::Scan);
    h.pitchUm[0] = h.pitchUm[1] = 50;
    h.originUm[0] = 10000;
    h.originUm[1] = 5000;
    h.fullUs = fullUs;
    for (int k = 0; k < 4; k++) {
      h.gainPermille[k] = 1000;
      h.offsets[k][0] = static_cast<int16_t>(k % 2 ? 1 : -2);
    }
    return h;
  }
  uv::MotionModel machine() const {
    uv::MotionModel m{};
    m.vmaxUmS[0] = m.vmaxUmS[1] = static_cast<uint32_t>(config.milli(Key::SpeedTravel));
    m.accelUmS2[0] = static_cast<uint32_t>(config.milli(Key::AccelX));
    m.accelUmS2[1] = static_cast<uint32_t>(config.milli(Key::AccelY));
    m.stepsMilli[0] = static_cast<uint32_t>(config.milli(Key::StepsX));
    m.stepsMilli[1] = static_cast<uint32_t>(config.milli(Key::StepsY));
    return m;
  }
  uint32_t us() const { return static_cast<uint32_t>(rig.now / 2); }
  // One main-loop pass, then the step interrupt until the next, the G delivered at its moment.
  void loop() {
    nano.advance(us());
    link.poll(us());
    rig.motion.poll();
    const uint64_t next = rig.now + kLoopTicks;
    for (;;) {
      const uint64_t until = gAt && gAt < next ? gAt : next;
      rig.isrUntil(until);
      if (gAt && rig.now >= gAt) {
        nano.advance(static_cast<uint32_t>(gAt / 2));
        nano.write("G\n", 2);
        gAt = 0;
      }
      if (rig.now >= next) break;
    }
  }
  void SetUp() override {
    rig.onMark = [this](uint64_t t) {
      gAt = t + kGTicks;
      return true;
    };
    link.begin(us());
    for (int i = 0; i < 1200; i++) loop();  // the link identifies the Nano
  }
  // Runs the job to its end; returns the last step.
  ScanRun::Step run(ScanRun& s, const uv::JobHeader& h, uint32_t maxUs = 60000000) {
    ScanRun::Step st = ScanRun::Step::Busy;
    while (us() < maxUs) {
      st = s.poll(rig.motion, link, h, us());
      if (st == ScanRun::Step::End || st == ScanRun::Step::Failed) break;
      loop();
    }
    return st;
  }
  // A job of `cols` × `rows` cells at `fullUs` a full cell, planned and ready to run.
  struct Planned {
    Planned(ScanRunTest& t, uint16_t cols, uint16_t rows, uint32_t fullUs, bool gaps = false)
        : grid(gaps ? scandose::gapPattern(cols, rows) : scandose::testPattern(cols, rows)), h(t.job(cols, rows, fullUs)), cells(grid), m(t.machine()), planner(h, cells, m), scan(planner) {}
    std::vector<std::vector<uint8_t>> grid;
    uv::JobHeader h;
    uvtest::GridCells cells;
    uv::MotionModel m;
    uv::ScanPlanner planner;
    ScanRun scan;
  };
  scandose::Figures measure(const uv::JobHeader& h, const std::vector<std::vector<uint8_t>>& grid, const std::vector<double>& windowUs) {
    scandose::Track track;
    track.add(0, 0, 0);
    scandose::addSteps(track, rig.steps);
    const double spm[2] = {config.milli(Key::StepsX) / 1000.0, config.milli(Key::StepsY) / 1000.0};
    return scandose::measure(h, grid, scandose::lightsOf(nano.scanLight), track, spm, windowUs);
  }
};

}  // namespace

TEST_F(ScanRunTest, ExposesEveryCellItsDoseInPlaceOnTheMove) {
  Planned p(*this, 60, 11, 500);  // 500 µs at 50 µm: 100 mm/s, the axis's maximum
  ASSERT_FALSE(p.planner.mayFly());
  ScanRun& scan = p.scan;
  const uv::JobHeader& h = p.h;
  const uv::ScanPlanner& planner = p.planner;
  ASSERT_EQ(run(scan, h), ScanRun::Step::End) << "error " << int(scan.error());
  EXPECT_EQ(scan.passes(), planner.passes());
  EXPECT_GE(scan.passes(), 3);
  EXPECT_EQ(nano.lit(), 0);
  EXPECT_EQ(rig.engine.marksMissed(), 0);
  const scandose::Figures f = measure(h, p.grid, scandose::passWindows(h, p.grid, p.m));
  std::printf("[scan host] %d cells (%d lit), %u passes: worst dose error %.2f %% of full, worst centroid %.2f um, worst edge %.2f um (cell 50 um)\n",
              f.cells, f.lit, scan.passes(), f.worstDosePct, f.worstCentreUm, f.worstEdgeUm);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 50 / 4.0);
  EXPECT_LE(f.worstCentreUm, 50 / 4.0);
}

// A pass is confirmed as its light ends, while its stroke runs out (50 ms at 100 mm/s): every pass
// is done before its head is at rest, where it waited for the 10 ms Q after that rest before.
TEST_F(ScanRunTest, EachPassIsDoneWhileItsStrokeRunsOut) {
  Planned p(*this, 60, 11, 500);
  ScanRun::Step st = ScanRun::Step::Busy;
  uint32_t done = 0, whileMoving = 0;
  while (us() < 60000000) {
    st = p.scan.poll(rig.motion, link, p.h, us());
    if (st == ScanRun::Step::PassDone) {
      done++;
      if (!rig.motion.idle()) whileMoving++;
    }
    if (st == ScanRun::Step::End || st == ScanRun::Step::Failed) break;
    loop();
  }
  ASSERT_EQ(st, ScanRun::Step::End) << "error " << int(p.scan.error());
  EXPECT_EQ(done, p.planner.passes());
  EXPECT_EQ(whileMoving, done);
  EXPECT_TRUE(rig.motion.idle()) << "the job ends at rest";
}

// A filled block with the LEDs on adjacent rows: each pass starts where the last one stops, a hop of
// four rows (16 steps) in Y alone, which glides beside the last stroke's run-out (protocol/planner.md
// "Gliding"). Every cell keeps its dose in place, most of each hop's steps come while X still runs
// out, and the job takes what the planner prices it at.
TEST_F(ScanRunTest, TheHopToTheNextPassGlidesBesideTheRunOut) {
  const std::vector<std::vector<uint8_t>> grid(16, std::vector<uint8_t>(40, 255));
  uv::JobHeader h = job(40, 16, 2000);  // 25 mm/s passes: 12.5 ms run-outs
  for (int k = 0; k < 4; k++) h.offsets[k][0] = 0;
  uvtest::GridCells cells(grid);
  const uv::MotionModel m = machine();
  uv::ScanPlanner planner(h, cells, m);
  ScanRun scan(planner);
  while (!link.nanoClock().known() && us() < 10000000) loop();
  rig.steps.clear();
  const uint32_t startUs = us();
  ASSERT_EQ(run(scan, h), ScanRun::Step::End) << "error " << int(scan.error());
  const uint32_t tookUs = us() - startUs;
  ASSERT_EQ(scan.passes(), 4);
  // The hops: the Y steps after the first pass's mark. One glided beside a run-out when X steps in the
  // same direction come both before it and after it, less than 20 ms apart (a stroke still under way).
  ASSERT_FALSE(rig.marks.empty());
  uint32_t ySteps = 0, beside = 0;
  for (size_t i = 0; i < rig.steps.size(); i++) {
    if (!(rig.steps[i].axes & 2) || rig.steps[i].us2 < rig.marks.front()) continue;
    ySteps++;
    size_t b = i, j = i + 1;
    while (b > 0 && !(rig.steps[b].axes & 1)) b--;
    while (j < rig.steps.size() && !(rig.steps[j].axes & 1)) j++;
    if (j < rig.steps.size() && (rig.steps[b].axes & 1) && ((rig.steps[b].dirNeg ^ rig.steps[j].dirNeg) & 1) == 0 &&
        rig.steps[j].us2 - rig.steps[b].us2 < 40000)
      beside++;
  }
  const scandose::Figures f = measure(h, grid, scandose::passWindows(h, grid, m));
  std::printf("[scan host, gliding] %u passes in %.1f ms (planned %.1f ms): %u of %u Y steps beside X's run-out; worst dose error %.2f %% of full, worst edge %.2f um\n",
              scan.passes(), tookUs / 1e3, planner.estimateUs() / 1e3, beside, ySteps, f.worstDosePct, f.worstEdgeUm);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 50 / 4.0);
  EXPECT_EQ(rig.engine.underruns(), 0);
  EXPECT_EQ(ySteps, 3u * 16u);
  EXPECT_GE(beside, ySteps / 3) << "the hops glided beside the run-outs";
  EXPECT_NEAR(tookUs, static_cast<double>(planner.estimateUs()), 0.01 * planner.estimateUs() + 2000.0 * scan.passes());
}

// At 25 mm/s, under the axis's 100: the stretches between islands are flown, each back at the speed
// on the step and the tick the Nano's program expects.
TEST_F(ScanRunTest, FliesBlankStretchesAndKeepsEveryCellInPlace) {
  Planned p(*this, 200, 8, 2000, true);
  ASSERT_TRUE(p.planner.mayFly());
  while (!link.nanoClock().known() && us() < 10000000) loop();  // its passes wait for the Nano's clock
  const uint32_t startUs = us();
  uint32_t firstJumps = 0;
  for (int i = 0; i < 100 && !p.scan.passes() && !firstJumps; i++) {  // the first pass opens
    p.scan.poll(rig.motion, link, p.h, us());
    firstJumps = p.planner.jumps();
    loop();
  }
  EXPECT_GE(firstJumps, 3u);
  ASSERT_EQ(run(p.scan, p.h), ScanRun::Step::End) << "error " << int(p.scan.error());
  const uint32_t tookUs = us() - startUs;
  EXPECT_EQ(p.scan.passes(), p.planner.passes());
  EXPECT_EQ(nano.lit(), 0);
  EXPECT_EQ(rig.engine.marksMissed(), 0);
  EXPECT_EQ(rig.engine.underruns(), 0);
  // The head went faster than the pass's speed (2000 steps/s at 80 steps/mm): it flew.
  EXPECT_LT(shortestXStep(rig.steps), 2 * 500 * 3 / 4) << "no step faster than the pass's speed";
  const scandose::Figures f = measure(p.h, p.grid, scandose::passWindows(p.h, p.grid, p.m));
  std::printf("[scan host, flying] %d cells (%d lit), %u passes in %.2f s (planned %.2f s): worst dose error %.2f %% of full, worst centroid %.2f um, worst edge %.2f um\n",
              f.cells, f.lit, p.scan.passes(), tookUs / 1e6, p.planner.estimateUs() / 1e6, f.worstDosePct, f.worstCentreUm, f.worstEdgeUm);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 50 / 4.0);
  EXPECT_LE(f.worstCentreUm, 50 / 4.0);
  // In simulated time, the job took what the planner said (its moves are the time model's) within 1 %,
  // and 15 ms a pass for loading it and the Q that confirms it (this machine's overheadUs is 0); and
  // less than crossing every stretch at the speed would.
  EXPECT_NEAR(tookUs, static_cast<double>(p.planner.estimateUs()), 0.01 * p.planner.estimateUs() + 15000.0 * p.scan.passes());
  uvtest::GridCells cells(p.grid);
  uv::ScanPlanner crossing(p.h, cells, p.m);
  crossing.neverFly();
  uv::ScanPass pass;
  while (crossing.nextPass(pass)) {
  }
  std::printf("[scan host, flying] %u stretches flown in the first pass; crossing them would take %.2f s\n", firstJumps,
              crossing.estimateUs() / 1e6);
  EXPECT_LT(p.planner.estimateUs() + 200000, crossing.estimateUs());
}

TEST_F(ScanRunTest, APassTheNanoCutsForHeatFailsTheRunDark) {
  Planned p(*this, 400, 4, 500);  // one long pass: 0.2 s of windows
  ScanRun& scan = p.scan;
  const uv::JobHeader& h = p.h;
  ScanRun::Step st = ScanRun::Step::Busy;
  bool heated = false;
  while (us() < 10000000) {
    st = scan.poll(rig.motion, link, h, us());
    if (st == ScanRun::Step::End || st == ScanRun::Step::Failed) break;
    if (!heated && !nano.scanLight.empty() && us() > nano.scanLight.front().onUs + 50000) {
      nano.setTemps(900);  // 90 °C: over every limit, the Nano's own logic cuts the chain
      heated = true;
    }
    loop();
  }
  ASSERT_TRUE(heated);
  EXPECT_EQ(st, ScanRun::Step::Failed);
  EXPECT_EQ(scan.error(), 31);
  EXPECT_EQ(nano.lit(), 0);
  EXPECT_EQ(scan.passes(), 0);
}

TEST_F(ScanRunTest, AGTheUartCannotSendOnItsStepFailsThePass) {
  Planned p(*this, 30, 4, 500);
  ScanRun& scan = p.scan;
  const uv::JobHeader& h = p.h;
  rig.onMark = [](uint64_t) { return false; };  // as if a byte were still going out: no G
  EXPECT_EQ(run(scan, h), ScanRun::Step::Failed);
  EXPECT_EQ(scan.error(), 33);
  EXPECT_TRUE(nano.scanLight.empty());
}
