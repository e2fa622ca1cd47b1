// Exposure on the move on the real images (issue 19): the Mega image plans a streamed scan job pass
// by pass, loads the Nano image's programs, and its step interrupt sends each G on its marked step;
// the rig logs the head's steps and the Nano's LED pins, and every cell's dose and every LED edge
// is measured from them against the job (scan_dose.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <regex>

#include "grid_cells.h"
#include "printhead_link.h"
#include "scan.h"
#include "scan_board_fixture.h"

using namespace mega::jobs;

namespace {
// A photo's gray: 64 cells a row that change from cell to cell and row to row.
Grid photoLike(size_t rows, size_t cols = 64) {
  Grid g(rows, std::vector<uint8_t>(cols));
  for (size_t r = 0; r < g.size(); r++)
    for (size_t c = 0; c < g[r].size(); c++) g[r][c] = static_cast<uint8_t>(std::lround(127.5 + 127.5 * std::sin(c / 6.0 + r) * std::cos(r / 3.0 + c / 17.0)));
  return g;
}
// The machine as the Mega plans its jobs: at the link's speed it runs them at (kJobLinkBaud).
uv::MotionModel megaPlans() { return uv::MotionModel{{100000, 100000}, {2000000, 1500000}, 2000, 400, {0, 0}, {80000, 80000}, mega::kJobLinkBaud}; }

// The Nano's clock's clock against the Mega's, set before both boot: each board's 16 MHz comes from its own
// crystal or resonator, and a resonator is good to 0.5 %. The Mega measures the Nano's clock by W
// (nano_clock.h) and times every event on it; without that, a Nano 0.5 % off put 20 % of a cell's
// dose into its neighbour by the end of these 40 ms passes.
class ScanBoardTest : public ScanOnBoard, public ::testing::WithParamInterface<double> {
 protected:
  void SetUp() override {
    sim.nanoClock = GetParam();
    BoardTest::SetUp();
  }
  // The pass's programs (`programs`, each sealed by one K) each reported once, in order, their on-times
  // those of the Nano's pins on its own clock (its µs are the ones it counts) within 2 µs a stretch
  // (protocol/nano.md "O").
  void expectDoseReported(int programs) {
    const DoseFigures d = doseAgainstPins();
    EXPECT_EQ(std::count_if(sim.nanoLines.begin(), sim.nanoLines.end(), [](const std::string& l) { return l.rfind("K:", 0) == 0; }), programs);
    EXPECT_EQ(d.lines, programs);
    EXPECT_TRUE(d.inOrder);
    for (int k = 0; k < 4; k++) {
      EXPECT_NEAR(d.reportedUs[k], d.pinUs[k] * GetParam(), 2.0 * d.stretches[k] + 1) << "LED " << k;
      std::printf("[scan simavr, dose reported] LED %d: %d stretches, %.0f us on the pins (on the Nano's clock), %.0f us in %d DOSE: lines\n", k,
                  d.stretches[k], d.pinUs[k] * GetParam(), d.reportedUs[k], d.lines);
    }
  }
};

// A Nano 0.3 % fast, so the stretches flown are timed on a clock that is not the Mega's as well.
class ScanFlyingBoardTest : public ScanOnBoard {
 protected:
  void SetUp() override {
    sim.nanoClock = 1.003;
    BoardTest::SetUp();
  }
};
// A profile as scripts/mega-profile.py reads it: each instruction's byte address, cycles and runs.
void writeProfile(const std::vector<BoardSim::PcCount>& profile, const char* path) {
  std::FILE* out = std::fopen(path, "w");
  ASSERT_NE(out, nullptr) << path;
  for (size_t w = 0; w < profile.size(); w++)
    if (profile[w].runs)
      std::fprintf(out, "%zx %llu %llu\n", 2 * w, static_cast<unsigned long long>(profile[w].cycles), static_cast<unsigned long long>(profile[w].runs));
  std::fclose(out);
}
}  // namespace

INSTANTIATE_TEST_SUITE_P(NanoClocks, ScanBoardTest, ::testing::Values(1.0, 1.005, 0.995));

TEST_P(ScanBoardTest, AScanJobOnTheRealImagesGivesEveryCellItsDoseInPlace) {
  // 1-cell lines, runs of full cells and gray steps, at 100 µm and 1 ms a cell: 100 mm/s, the
  // axis's top speed, so no blank stretch is flown.
  const Grid g = scandose::testPattern(40, 10);
  const uv::JobHeader h = scanJob(g, 1000);
  const scandose::Figures f = expose(h, g, 3);  // 10 rows, 4 LEDs a row apart: 3 passes
  std::printf("[scan simavr] real Mega + Nano images, the Nano's clock %+.1f %%, %d cells (%d lit) in 3 passes: worst dose error %.2f %% of the full dose, "
              "worst LED edge %.2f um from its place, worst cell centroid %.2f um (cell 100 um; goals 2 %% and 25 um)\n",
              (GetParam() - 1) * 100, f.cells, f.lit, f.worstDosePct, f.worstEdgeUm, f.worstCentreUm);
  EXPECT_EQ(f.stray, 0);
  // The time the real images take against the planner's estimate (issue 39; printed, not a goal): the
  // estimate gives a pass's start kScanPassLoadUs and its end what kScanPassEndUs from its light's end
  // outlasts the run-out (ScanPass::endUs), where the Mega also plans
  // the next pass (its link check writes every event's line, some 300 µs each: kProgramEventUs) and
  // makes its first two programs' lines before the stroke can start.
  const uv::MotionModel m = megaPlans();
  uvtest::GridCells cells(g);
  uv::ScanPlanner planner(h, cells, m);
  uv::ScanPass p;
  uint32_t passes = 0, events = 0, t;
  uint8_t state;
  for (; planner.nextPass(p); passes++)
    while (planner.nextEvent(t, state)) events++;
  const double estimateUs = static_cast<double>(planner.estimateUs()), beyondUs = jobUs - estimateUs;
  std::printf("[scan simavr, time] the job took %.1f ms on the real images, the planner's estimate %.1f ms (%.2fx): %.1f ms a pass beyond it, "
              "%u events in %u passes (%.0f us an event)\n",
              jobUs / 1e3, estimateUs / 1e3, jobUs / estimateUs, beyondUs / passes / 1e3, events, passes, beyondUs / events);
  // Between passes: from a pass's last light to the first step of the hop to the next (which glides
  // from the moment the next pass has opened: the Mega plans it then, its link check walking every
  // event of it). Printed, not a goal; the planner counts kScanPassEndUs for it (planner.md "Gliding").
  std::printf("[scan simavr, time] from a pass's last light to its hop's first step: %s ms (the planner counts %u us)\n", turnsMs().c_str(), uv::kScanPassEndUs);
  // The goal. Measured 1.02 %, and 0.55 % and 0.95 % with the Nano's clock 0.5 % fast and slow
  // (2.27 % before the Nano's timer read its next event inline and the step interrupt held the head
  // back for a late G). It moves by about half a percent with unrelated changes to the images (0.55
  // to 1.60 % seen): each pass's light runs 4 to 11 µs behind the head, by how late the Nano's
  // receive interrupt noted the G's newline, and of two events a few µs apart the second comes up
  // to 5 µs late (the Nano needs about 9 µs from one edge to the next: nano_sim_tests "Closer").
  // Those µs weigh four times less in the flying test's 4 ms cells (0.14 to 0.29 % there).
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}

// Two passes of the photo-like gray (below) at 2 ms a cell: what opening the second pass costs the
// real Mega between them, against the planner's estimate (printed, not a goal: planner.md "Gliding").
TEST_F(ScanOnBoard, TwoPhotoLikePassesOpenOneAfterTheOther) {
  const Grid g = photoLike(8);
  const uv::JobHeader h = scanJob(g, 2000);
  const scandose::Figures f = expose(h, g, 2, 2, scandose::passWindows(h, g, megaPlans()));
  // The planner's own count of each pass's events, and its estimate.
  const uv::MotionModel m = megaPlans();
  uvtest::GridCells cells(g);
  uv::ScanPlanner plan(h, cells, m);
  std::vector<uint32_t> events;
  uint32_t t;
  uint8_t state;
  for (uv::ScanPass p; plan.nextPass(p);)
    for (events.push_back(0); plan.nextEvent(t, state);) events.back()++;
  ASSERT_EQ(events.size(), 2u);
  std::printf("[scan simavr, photo-like turn] two passes of %u and %u events: from the first's last light to the hop's first step %s ms "
              "(the planner counts %u us, and its estimate of the job is %.1f ms); worst dose error %.2f %%\n",
              events[0], events[1], turnsMs().c_str(), uv::kScanPassEndUs, plan.estimateUs() / 1e3, f.worstDosePct);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
}

// What opening a pass costs the real Mega, for a photo-like pass of `cols` columns streamed (no card):
// nextPass() in all (its layout, the link check's walks of the pass's events at each window tried,
// and the rest: finding its rows, its motion, its cursors opened for its events), and its layouts
// alone (ScanPlanner::layout: one look at each cell of the pass's rows). A card job opens its passes
// from what M29 kept (kept_pass.h), with neither: what is left is the rest. Printed, not a goal
// (docs/planner.md "What P10 leaves out").
class LayoutOnBoard : public ScanOnBoard, public ::testing::WithParamInterface<size_t> {};

TEST_P(LayoutOnBoard, OpeningAPassCostsTheMegaItsLayoutAndLinkWalksAndLittleElse) {
  const Grid g = photoLike(4, GetParam());
  const uv::JobHeader h = scanJob(g, 2000);
  // The link check's walk (outrunsLink, inlined) makes the pass's program lines: ProgramLines::next,
  // which also makes them as the pass runs, after nextPass() has returned.
  const std::string nextPass = "_ZN2uv11ScanPlanner8nextPass", layout = "_ZN2uv11ScanPlanner6layout", lines = "_ZN2uv12ProgramLines4next",
                    load = "_ZN2uv8LinkLoad3add", reopen = "_ZN2uv11ScanPlanner8openPass";
  for (const std::string& f : {nextPass, layout, lines, load, reopen}) ASSERT_TRUE(sim.timeCalls(f)) << f;
  // UV_MEGA_PROFILE=<file>: those calls' cycles alone, by instruction (scripts/mega-profile.py).
  std::vector<BoardSim::PcCount> profile;
  const char* profileTo = std::getenv("UV_MEGA_PROFILE");
  if (profileTo) {
    sim.megaProfile = &profile;
    sim.profileTimedOnly = true;
  }
  expose(h, g, 1, 1, scandose::passWindows(h, g, megaPlans()));
  sim.megaProfile = nullptr;
  if (profileTo) writeProfile(profile, profileTo);
  // nextPass() is called each poll while the rows stream in (starved), and once more at the end: the
  // longest call opened the job's one pass.
  const auto& calls = sim.timedCalls(nextPass);
  ASSERT_FALSE(calls.empty());
  const BoardSim::TimedCall open = *std::max_element(calls.begin(), calls.end(), [](const auto& a, const auto& b) { return a.cycles < b.cycles; });
  auto within = [&](const std::string& f, size_t& n, uint64_t& longest) {
    uint64_t sum = 0;
    n = 0;
    longest = 0;
    for (const BoardSim::TimedCall& c : sim.timedCalls(f))
      if (c.from >= open.from && c.to <= open.to) {
        sum += c.cycles;
        n++;
        longest = std::max(longest, c.cycles);
      }
    return sum / BoardSim::kCyclesPerUs / 1e3;
  };
  size_t layouts, made, loaded, opens;
  uint64_t longest, unused;
  const double layoutMs = within(layout, layouts, longest), openMs = open.cycles / BoardSim::kCyclesPerUs / 1e3;
  // The link check's walks: their lines, each weighed by LinkLoad::add, and the cursors opened again
  // after each walk and each layout but the last (ScanPlanner::openPass).
  const double walkMs = within(lines, made, unused) + within(load, loaded, unused);
  const double reopenMs = within(reopen, opens, unused), oneOpenMs = opens ? reopenMs / opens : 0;
  // What a pass opened as kept (a card job's) still runs: nextPass() less its layouts, walks and
  // reopenings but one.
  const double keptMs = openMs - layoutMs - walkMs - (reopenMs - oneOpenMs);
  std::printf("[scan simavr, opening a pass] %zu columns: nextPass %.2f ms, of which %zu layouts %.2f ms (the longest %.2f ms, %.0f us a column), "
              "the link check's walks %.2f ms (%zu program lines) and %zu cursor openings %.2f ms; a pass opened as kept would leave %.2f ms\n",
              g[0].size(), openMs, layouts, layoutMs, longest / BoardSim::kCyclesPerUs / 1e3, longest / BoardSim::kCyclesPerUs / g[0].size(), walkMs, made, opens,
              reopenMs, keptMs);
  EXPECT_GE(layouts, GetParam() < 32 ? 1u : 2u);  // the job's window, and from 32 columns the link cap's
  EXPECT_GT(made, 0u);
  EXPECT_GT(keptMs, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Columns, LayoutOnBoard, ::testing::Values(16, 32, 64));

// testPattern's rows 8 to 11 as one pass at 1 ms a cell: two gray rows, 218 events, a chain of four
// programs. The Nano holds two, so the third goes out only once the first has played and the Mega's
// Q has learnt so, and must be in before the second ends: the planner slows the pass until each
// program fits the time the one before it plays (planner.md "The printhead link"). Before that rule
// the chain was cut short (Q pass 5).
TEST_P(ScanBoardTest, AChainOfFourProgramsLoadsEachInTimeAndGivesEveryCellItsDose) {
  const Grid all = scandose::testPattern(40, 12);
  const Grid g(all.begin() + 8, all.end());
  const uv::JobHeader h = scanJob(g, 1000);
  uvtest::GridCells cells(g);
  const uv::MotionModel m = megaPlans();
  uv::ScanPlanner planner(h, cells, m);
  uv::ScanPass p;
  ASSERT_TRUE(planner.nextPass(p));
  const uint32_t windowUs = planner.passMotion().windowUs;
  const scandose::Figures f = expose(h, g, 1, 1, std::vector<double>(h.rows, windowUs));
  const LinkFigures link = linkFigures();
  std::printf("[scan simavr, four programs] real Mega + Nano images, the Nano's clock %+.1f %%, %d cells (%d lit) in 1 pass at a %u us window "
              "(the job's 1000): worst dose error %.2f %% of the full dose, worst LED edge %.2f um from its place, worst cell centroid %.2f um; "
              "%d programs waited for a buffer: longest relay %.0f us (the planner allows %u), least slack %.0f us\n",
              (GetParam() - 1) * 100, f.cells, f.lit, windowUs, f.worstDosePct, f.worstEdgeUm, f.worstCentreUm, link.waited, link.relayMaxUs,
              uv::kProgramRelayUs, link.slackMinUs);
  EXPECT_EQ(link.waited, 2);
  expectDoseReported(4);
  EXPECT_LE(link.relayMaxUs, uv::kProgramRelayUs);
  EXPECT_GT(link.slackMinUs, 0);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}

// A photo's pass (bench P11's photo: a gray that changes from cell to cell and row to row, so every
// LED switches twice in nearly every cell): some 7 events a cell, a chain of 7 programs that the link
// caps at a window of its own, near the fastest the relay allows. Each program after the first two
// must go out within the relay of the Nano freeing its buffer, and be armed before the one before it
// ends, while both hosts poll the Mega.
TEST_P(ScanBoardTest, APhotoLikePassLoadsEachProgramWithinTheRelay) {
  const Grid g = photoLike(4);
  const uv::JobHeader h = scanJob(g, 2000);
  uvtest::GridCells cells(g);
  const uv::MotionModel m = megaPlans();
  uv::ScanPlanner planner(h, cells, m);
  uv::ScanPass p;
  ASSERT_TRUE(planner.nextPass(p));
  const uint32_t windowUs = planner.passMotion().windowUs;
  pollBothHosts = true;  // and the panel redraws: the longest main-loop passes, which the relay waits on
  // UV_MEGA_PROFILE=<file>: the Mega's cycles over the job by instruction (the Nano at its nominal
  // clock), for scripts/mega-profile.py.
  std::vector<BoardSim::PcCount> profile;
  const char* profileTo = GetParam() == 1.0 ? std::getenv("UV_MEGA_PROFILE") : nullptr;
  if (profileTo) sim.megaProfile = &profile;
  const scandose::Figures f = expose(h, g, 1, 1, std::vector<double>(h.rows, windowUs));
  sim.megaProfile = nullptr;
  if (profileTo) writeProfile(profile, profileTo);
  const LinkFigures link = linkFigures();
  std::printf("[scan simavr, photo-like] real Mega + Nano images, the link at %u baud, the Nano's clock %+.1f %%, %d cells (%d lit) in 1 pass at a %u us window "
              "(the job's 2000, capped for the link): worst dose error %.2f %% of the full dose, worst LED edge %.2f um from its place, "
              "worst cell centroid %.2f um; %d programs waited for a buffer: longest relay %.0f us (the planner allows %u), least slack %.0f us\n",
              mega::kJobLinkBaud, (GetParam() - 1) * 100, f.cells, f.lit, windowUs, f.worstDosePct, f.worstEdgeUm, f.worstCentreUm, link.waited, link.relayMaxUs,
              uv::kProgramRelayUs, link.slackMinUs);
  EXPECT_GT(windowUs, h.fullUs);  // the link, not the light, sets its pace
  // At the raised speed (protocol/nano.md "Link speed"): the Mega asked it, the Nano took it, and it
  // never fell back (a fall-back drops the programs, and the pass would have failed). A board that
  // does not raise (mega::kRaiseNanoLink false) sends no L at all.
  const auto& toNano = sim.nanoLines;
  const auto& fromNano = sim.nanoReplies;
  const std::string raise = "L:" + std::to_string(mega::kNanoFastBaud);
  const auto asked = std::find(toNano.begin(), toNano.end(), raise);
  if (!mega::kRaiseNanoLink) {
    EXPECT_EQ(asked, toNano.end());
  } else {
    ASSERT_NE(asked, toNano.end());
    ASSERT_NE(asked + 1, toNano.end());
    EXPECT_EQ(*(asked + 1), "V");  // the probe at the new speed
    EXPECT_EQ(std::count(fromNano.begin(), fromNano.end(), raise), std::count(toNano.begin(), toNano.end(), raise));
    EXPECT_GE(std::count(fromNano.begin(), fromNano.end(), raise), 1);
  }
  EXPECT_GE(link.waited, 4);
  expectDoseReported(8);
  EXPECT_LE(link.relayMaxUs, uv::kProgramRelayUs);
  EXPECT_GT(link.slackMinUs, 0);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}

// Islands of lit cells far apart at 4 ms a 100 µm cell, 25 mm/s: the Mega flies the stretches
// between them (Motion::StrokeJump), up to the axis's 100 mm/s, and is back at the pass's speed on
// the step and the tick the Nano's program expects.
TEST_F(ScanFlyingBoardTest, FlownStretchesKeepEveryCellItsDoseInPlace) {
  const Grid g = scandose::gapPattern(150, 8);
  const uv::JobHeader h = scanJob(g, 4000);
  pollBothHosts = true;  // and the panel redraws: the heaviest run these images can have (no card here)
  const scandose::Figures f = expose(h, g, 2);
  EXPECT_GT(espHeard, 3);
  const double fastest = fastestX();
  unsigned loopMaxUs = 0, underruns = 1;
  diagnostics(loopMaxUs, underruns);
  std::printf("[scan simavr, flying] real Mega + Nano images, the Nano's clock +0.3 %%, %d cells (%d lit) in 2 passes, the head up to %.0f mm/s "
              "(the passes' speed 25): worst dose error %.2f %% of the full dose, worst LED edge %.2f um from its place, worst cell centroid %.2f um; "
              "longest main-loop pass while the last pass ran %u us (the queued segments cover 40000 us)\n",
              f.cells, f.lit, fastest / 80, f.worstDosePct, f.worstEdgeUm, f.worstCentreUm, loopMaxUs);
  EXPECT_GT(fastest / 80, 50.0);  // it flew
  EXPECT_EQ(underruns, 0u);  // cutting the stretches into segments kept ahead of the step interrupt
  EXPECT_LT(loopMaxUs, 20000u);  // half of what the queue covers
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}
