// Host tests of mixed mode (planner.md "Mixed mode"): its golden plans, the
// choice of each band and pass, and a mixed job planned while its rows arrive.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "grid_cells.h"
#include "job_json_fixture.h"
#include "machine_json_fixture.h"
#include "mixed_json_fixture.h"
#include "planner.h"
#include "scan.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace {

void checkMixedGolden(const char* file) {
  const json v = loadVectors(file);
  ASSERT_GE(v["cases"].size(), 10u) << file;
  int scans = 0, stops = 0, bands = 0;
  for (const json& c : v["cases"]) {
    std::vector<std::vector<uint8_t>> rows;
    for (const auto& r : c["job"]["gridData"]) rows.emplace_back(r.begin(), r.end());
    const JobHeader h = headerFrom(c["job"]);
    ASSERT_EQ(h.strategy, Strategy::Mixed) << c["name"];
    EXPECT_EQ(mixedPlanJson(h, rows, machineFrom(c["machine"])), c["mixed"]) << c["name"];
    for (const json& p : c["mixed"]["passes"]) {
      (p["scan"].get<bool>() ? scans : stops)++;
      if (p.contains("band")) bands++;
    }
  }
  // The vectors bind both ways of exposing a pass, and bands of stops.
  EXPECT_GT(scans, 5);
  EXPECT_GT(stops, 5);
  EXPECT_GT(bands, 2);
  std::printf("[vectors] %s: %zu mixed plans checked (C++), %d scan passes and %d of stops (%d of them bands)\n", file, v["cases"].size(), scans, stops, bands);
}

const MotionModel kMachine{{150000, 100000}, {3000000, 2000000}, 2000, 1500, {0, 0}, {80000, 80000}};

JobHeader mixedJob(uint16_t cols, uint16_t rows) {
  JobHeader h{};
  h.cols = cols;
  h.rows = rows;
  h.pitchUm[0] = h.pitchUm[1] = 50;
  h.originUm[0] = 1000;
  h.originUm[1] = 2000;
  h.map = DoseMap::Linear;
  h.fullUs = 2000;
  h.strategy = Strategy::Mixed;
  for (int k = 0; k < 4; k++) {
    h.gainPermille[k] = 1000;
    h.offsets[k][1] = static_cast<int16_t>(k);
  }
  return h;
}

}  // namespace

TEST(MixedGolden, ReproducesItsOwnPlans) { checkMixedGolden("mixed-cpp.json"); }

// A few dots far apart: the five passes are one band (planner.md "Bands"), cheaper as one group of
// stops than pass by pass, and its stops are `shortest`'s column by column, with its estimate to the µs.
TEST(MixedPlanner, SparseDotsAreABandOfShortestStops) {
  JobHeader h = mixedJob(300, 24);
  std::vector<std::vector<uint8_t>> rows(24, std::vector<uint8_t>(300, 0));
  rows[0][7] = 255;
  rows[5][250] = 90;
  rows[9][40] = rows[9][41] = 200;
  rows[17][299] = 255;
  rows[22][0] = 30;
  GridCells cells(rows), stopCells(rows);
  ScanPlanner mixed(h, cells, kMachine);
  JobHeader shortest = h;
  shortest.strategy = Strategy::Shortest;
  Planner stopPlanner(shortest, stopCells, kMachine);
  PlanClock clock(shortest, kMachine);
  ScanPass p;
  ASSERT_TRUE(mixed.nextPass(p));
  EXPECT_TRUE(p.stops);
  EXPECT_EQ(p.band, 5);
  EXPECT_LT(p.stopsUs, p.scanUs);  // the band of stops against the passes one by one
  EXPECT_EQ(p.first, 0);
  EXPECT_EQ(p.last, 299);
  Stop a, b;
  int stops = 0;
  while (mixed.nextStop(a)) {
    ASSERT_TRUE(stopPlanner.next(b));
    clock.add(b);
    stops++;
    EXPECT_EQ(a.hx, b.hx);
    EXPECT_EQ(a.hy, b.hy);
    for (int k = 0; k < 4; k++) EXPECT_EQ(a.us[k], b.us[k]);
  }
  EXPECT_FALSE(stopPlanner.next(b));
  EXPECT_EQ(stops, 6);
  EXPECT_FALSE(mixed.nextPass(p));
  EXPECT_EQ(mixed.passes(), 5);
  EXPECT_EQ(mixed.estimateUs(), clock.totalUs());
  EXPECT_EQ(mixed.estimateUs(), p.stopsUs);
}

// A band of sparse passes between dense ones: the dense band goes pass by pass on the move, the sparse
// one as a band of stops, and the estimate is the two bands' cheaper prices.
TEST(MixedPlanner, EachBandTakesTheCheaperWay) {
  JobHeader h = mixedJob(200, 64);
  std::vector<std::vector<uint8_t>> rows(64, std::vector<uint8_t>(200, 0));
  for (int y = 0; y < 32; y++)
    for (int x = 10; x < 190; x++) rows[y][x] = 255;
  for (int y = 32; y < 64; y++) rows[y][(y * 53) % 200] = 255;
  GridCells cells(rows);
  ScanPlanner mixed(h, cells, kMachine);
  ScanPass p;
  int scans = 0, bands = 0;
  uint64_t total = 0;
  while (mixed.nextPass(p)) {
    if (!p.stops) {
      scans++;
      EXPECT_EQ(p.band, 0);
      EXPECT_LT(p.scanUs, p.stopsUs);
      total += p.scanUs;
      uint32_t t;
      uint8_t m;
      while (mixed.nextEvent(t, m)) {
      }
      continue;
    }
    bands++;
    EXPECT_EQ(p.band, 8);
    EXPECT_LT(p.stopsUs, p.scanUs);
    total += p.stopsUs;
    Stop s;
    int n = 0;
    while (mixed.nextStop(s)) n++;
    EXPECT_EQ(n, 32);
  }
  EXPECT_EQ(scans, 8);
  EXPECT_EQ(bands, 1);
  EXPECT_EQ(mixed.passes(), 16);
  EXPECT_EQ(mixed.estimateUs(), total);
}

// Full rows: every pass is cheaper on the move, and the passes are the scan planner's, events and all.
TEST(MixedPlanner, DenseRowsAreTheScanPasses) {
  JobHeader h = mixedJob(60, 12);
  std::vector<std::vector<uint8_t>> rows(12, std::vector<uint8_t>(60, 0));
  for (int y = 0; y < 12; y++)
    for (int x = 3; x < 57; x++) rows[y][x] = static_cast<uint8_t>(128 + (x * 7 + y) % 128);
  GridCells cells(rows), scanCells(rows);
  ScanPlanner mixed(h, cells, kMachine);
  JobHeader scanHeader = h;
  scanHeader.strategy = Strategy::Scan;
  ScanPlanner scan(scanHeader, scanCells, kMachine);
  ScanPass p, q;
  int passes = 0;
  while (mixed.nextPass(p)) {
    ASSERT_TRUE(scan.nextPass(q));
    passes++;
    EXPECT_FALSE(p.stops);
    EXPECT_LT(p.scanUs, p.stopsUs);
    EXPECT_EQ(p.strokeUs, q.strokeUs);
    Stop s;
    EXPECT_FALSE(mixed.nextStop(s));  // a scan pass has no stops
    uint32_t t1, t2;
    uint8_t m1, m2;
    int events = 0;
    while (mixed.nextEvent(t1, m1)) {
      ASSERT_TRUE(scan.nextEvent(t2, m2));
      EXPECT_EQ(t1, t2);
      EXPECT_EQ(m1, m2);
      events++;
    }
    EXPECT_FALSE(scan.nextEvent(t2, m2));
    EXPECT_GT(events, 0);
  }
  EXPECT_FALSE(scan.nextPass(q));
  EXPECT_EQ(passes, 3);
  EXPECT_EQ(mixed.estimateUs(), scan.estimateUs());
}

// Dense bands between sparse ones: both ways in one job, each pass the cheaper of its two prices, and
// the estimate their sum; never slower than either pure mode on this job.
TEST(MixedPlanner, EachPassTakesTheCheaperWay) {
  JobHeader h = mixedJob(80, 32);
  std::vector<std::vector<uint8_t>> rows(32, std::vector<uint8_t>(80, 0));
  for (int y = 0; y < 32; y++) {
    if ((y / 4) % 2 == 0)
      for (int x = 0; x < 80; x++) rows[y][x] = 255;
    else if (y % 4 == 1)
      rows[y][(y * 37) % 80] = 255;
  }
  GridCells cells(rows);
  ScanPlanner mixed(h, cells, kMachine);
  ScanPass p;
  uint64_t sum = 0;
  int scans = 0, stopPasses = 0;
  while (mixed.nextPass(p)) {
    sum += std::min(p.scanUs, p.stopsUs);
    (p.stops ? stopPasses : scans)++;
    EXPECT_EQ(p.stops, p.stopsUs <= p.scanUs);
    Stop s;
    while (mixed.nextStop(s)) {
    }
    uint32_t t;
    uint8_t m;
    while (mixed.nextEvent(t, m)) {
    }
  }
  EXPECT_EQ(scans + stopPasses, 8);
  EXPECT_GE(scans, 4);  // the dense passes at least
  EXPECT_GE(stopPasses, 1);
  EXPECT_EQ(mixed.estimateUs(), sum);
  GridCells scanCells(rows), stopCells(rows);
  JobHeader scanHeader = h, serpentine = h;
  scanHeader.strategy = Strategy::Scan;
  serpentine.strategy = Strategy::Serpentine;
  ScanPlanner scan(scanHeader, scanCells, kMachine);
  while (scan.nextPass(p)) {
    uint32_t t;
    uint8_t m;
    while (scan.nextEvent(t, m)) {
    }
  }
  Planner stops(serpentine, stopCells, kMachine);
  PlanClock clock(serpentine, kMachine);
  for (Stop s; stops.next(s);) clock.add(s);
  std::printf("[mixed] 8 passes, 4 dense and 4 of one dot: %d scan and %d stop passes, mixed %.3f s, scan %.3f s, serpentine stops %.3f s\n",
              scans, stopPasses, mixed.estimateUs() / 1e6, scan.estimateUs() / 1e6, clock.totalUs() / 1e6);
  EXPECT_LT(mixed.estimateUs(), scan.estimateUs());
  EXPECT_LT(mixed.estimateUs(), clock.totalUs());
}

// Fed a row at a time, as a stream arrives (planner.md "Planning while rows arrive"), the mixed plan is
// the whole job's: the same bands, passes, ways, stops and estimate; a band of stops among them. And
// so it is with each band priced a pass a call, as the Mega asks (sliceBands).
TEST(MixedPlanner, PlansWhileRowsArrive) {
  JobHeader h = mixedJob(70, 76);
  h.offsets[1][0] = 2;
  h.offsets[2][0] = -1;
  std::vector<std::vector<uint8_t>> rows(76, std::vector<uint8_t>(70, 0));
  for (int y = 0; y < 40; y++)
    for (int x = 0; x < 70; x++) rows[y][x] = (y % 6 < 3 ? (x * 3 + y) % 4 != 0 : (x * 11 + y * 7) % 31 == 0) ? static_cast<uint8_t>(60 + (x + y) % 190) : 0;
  for (int y = 40; y < 76; y += 2) rows[y][y % 4 ? 3 : 66] = 255;  // a cell near either end: bands of stops
  int bands = 0, pricings = 0;
  auto run = [&](bool streamed, bool slice) {
    GridCells cells(rows);
    ScanPlanner planner(h, cells, kMachine);
    if (slice) planner.sliceBands();
    std::vector<std::vector<int64_t>> out;
    uint16_t known = 0;
    if (streamed) planner.setKnownRows(known);
    for (;;) {
      ScanPass p;
      if (!planner.nextPass(p)) {
        if (planner.pricing()) {
          pricings++;
          EXPECT_FALSE(planner.inStopPass());
          continue;
        }
        if (!planner.starved()) break;
        EXPECT_LT(known, h.rows);
        planner.setKnownRows(++known);
        continue;
      }
      out.push_back({p.hy, p.descending, p.stops, p.band, static_cast<int64_t>(p.scanUs), static_cast<int64_t>(p.stopsUs)});
      bands += p.band > 0;
      Stop s;
      while (planner.nextStop(s)) out.push_back({s.hx, s.hy, s.us[0], s.us[1], s.us[2], s.us[3]});
      uint32_t t;
      uint8_t m;
      while (planner.nextEvent(t, m)) out.push_back({t, m});
    }
    out.push_back({static_cast<int64_t>(planner.estimateUs())});
    return out;
  };
  const auto whole = run(false, false), streamed = run(true, false), sliced = run(true, true);
  EXPECT_GT(whole.size(), 20u);
  EXPECT_EQ(streamed, whole);
  EXPECT_EQ(sliced, whole);  // a band priced a pass a call (sliceBands), as the Mega does
  EXPECT_GE(bands, 3);  // one a run
  EXPECT_GT(pricings, 8);
}
