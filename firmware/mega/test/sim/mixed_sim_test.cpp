// A mixed job on the real images (issue 28): the Mega image plans a streamed job pass by pass, runs
// its dense passes on the move (the Nano image's programs, each G on its marked step) and its sparse
// ones stop by stop (F), a band of them column by column, and every cell's dose and every LED edge is measured from the head's steps
// and the Nano's LED pins against the job (scan_dose.h).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "grid_cells.h"
#include "printhead_link.h"
#include "scan.h"
#include "scan_board_fixture.h"

namespace {

// The Mega image's defaults (firmware/mega/CONFIG.md) as its planner sees them, from the origin where
// G28 leaves the head: 100 mm/s (speed.travel), 2000 and 1500 mm/s², 2 ms settle, 400 µs a stop.
const uv::MotionModel kDefaults{{100000, 100000}, {2000000, 1500000}, 2000, 400, {0, 0}, {80000, 80000}, mega::kJobLinkBaud};

// What the planner makes of the job on that machine: each pass's way ('s' on the move, 'x' stops, 'b' a
// band of stops: planner.md "Bands"),
// the job's progress count, its passes on the move, and the window of the pass that exposes each row.
struct Ways {
  std::string ways;
  int steps = 0, strokes = 0;
  std::vector<double> windowOfRow;
};
Ways waysOf(const uv::JobHeader& h, const Grid& g) {
  uvtest::GridCells cells(g);
  uv::ScanPlanner planner(h, cells, kDefaults);
  Ways out;
  out.windowOfRow.assign(h.rows, 0);
  uv::ScanPass p;
  while (planner.nextPass(p)) {
    out.ways += p.band ? 'b' : p.stops ? 'x' : 's';
    if (!p.stops) {
      out.strokes++;
      out.steps++;
      for (int k = 0; k < 4; k++)
        if (p.hy + h.offsets[k][1] >= 0 && p.hy + h.offsets[k][1] < h.rows) out.windowOfRow[p.hy + h.offsets[k][1]] = planner.passMotion().windowUs;
    }
    uv::Stop s;
    while (planner.nextStop(s)) out.steps++;
    uint32_t t;
    uint8_t m;
    while (planner.nextEvent(t, m)) {
    }
  }
  return out;
}

// The dense passes here are the first four rows, as scan_sim_test's first pass (testPattern's rows 8
// to 11, a chain of four programs, run in scan_sim_test).
using MixedBoardTest = ScanOnBoard;

}  // namespace

TEST_F(MixedBoardTest, AMixedJobOnTheRealImagesScansTheDensePassesAndStopsForThePadsEveryCellItsDoseInPlace) {
  const Grid g = scandose::mixedPattern(40, 16);
  uv::JobHeader h = scanJob(g, 1000);  // 1 ms a 100 µm cell: 100 mm/s, the axis's top speed
  h.strategy = uv::Strategy::Mixed;
  const Ways w = waysOf(h, g);
  ASSERT_EQ(w.ways, "sxsx");  // 16 rows, 4 LEDs a row apart: 4 passes, the dense ones on the move
  const scandose::Figures f = expose(h, g, w.steps, w.strokes, w.windowOfRow);
  int fires = 0;
  for (const std::string& l : sim.nanoLines) fires += !l.empty() && l[0] == 'F';
  std::printf("[mixed simavr] real Mega + Nano images, passes %s ('s' on the move, 'x' stops; %d F lines), %d cells (%d lit): worst dose error %.2f %% of "
              "the full dose, worst LED edge %.2f um from its place, worst cell centroid %.2f um (cell 100 um; goals 2 %% and 25 um)\n",
              w.ways.c_str(), fires, f.cells, f.lit, f.worstDosePct, f.worstEdgeUm, f.worstCentreUm);
  EXPECT_EQ(fires, w.steps - w.strokes);  // each stop by F, the rest in the chains
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}

// The same with a band of stops (planner.md "Bands"): after the first band of 8 passes, taken pass by
// pass, the next 4 passes of one cell near either end of every other row go as one band of stops,
// column by column, each stop by F.
TEST_F(MixedBoardTest, AMixedJobOnTheRealImagesTakesASparseBandAsOneBandOfStopsEveryCellItsDoseInPlace) {
  const Grid g = scandose::bandedPattern(40, 48, 16);
  uv::JobHeader h = scanJob(g, 1000);
  h.strategy = uv::Strategy::Mixed;
  const Ways w = waysOf(h, g);
  ASSERT_EQ(w.ways, "sxsxxxxxb");
  const scandose::Figures f = expose(h, g, w.steps, w.strokes, w.windowOfRow);
  int fires = 0;
  for (const std::string& l : sim.nanoLines) fires += !l.empty() && l[0] == 'F';
  unsigned loopMaxUs = 0, underruns = 1;
  diagnostics(loopMaxUs, underruns);  // the longest main-loop pass of the run: planning a band is one
  std::printf("[mixed simavr] real Mega + Nano images, passes %s ('b' a band of stops; %d F lines), %d cells (%d lit): worst dose error %.2f %% of "
              "the full dose, worst LED edge %.2f um from its place, worst cell centroid %.2f um (cell 100 um; goals 2 %% and 25 um); "
              "longest main-loop pass %u us\n",
              w.ways.c_str(), fires, f.cells, f.lit, f.worstDosePct, f.worstEdgeUm, f.worstCentreUm, loopMaxUs);
  EXPECT_EQ(underruns, 0u);
  EXPECT_EQ(fires, w.steps - w.strokes);
  EXPECT_EQ(f.stray, 0);
  EXPECT_LE(f.worstDosePct, 2.0);
  EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  EXPECT_LE(f.worstCentreUm, 100 / 4.0);
}
