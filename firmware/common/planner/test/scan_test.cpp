// Host tests of the C++ scan planner: its golden scan plans, switch times of
// small features, and a pass at a time without the heap.
#include "scan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <set>
#include <vector>

#include "grid_cells.h"
#include "job_json_fixture.h"
#include "machine_json_fixture.h"
#include "planner.h"
#include "scan_json_fixture.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace uvtest {
extern std::atomic<long> allocations;  // counted by planner_test.cpp's operator new
}

namespace {

void checkScanGolden(const char* file) {
  const json v = loadVectors(file);
  ASSERT_GT(v["cases"].size(), 10u) << file;
  for (const json& c : v["cases"]) {
    std::vector<std::vector<uint8_t>> rows;
    for (const auto& r : c["job"]["gridData"]) rows.emplace_back(r.begin(), r.end());
    const JobHeader h = headerFrom(c["job"]);
    EXPECT_EQ(scanPlanJson(h, rows, machineFrom(c["machine"])), c["scan"]) << c["name"];
  }
  std::printf("[vectors] %s: %zu scan plans checked (C++)\n", file, v["cases"].size());
}

// The random jobs' source: xorshift32, a number below n each call.
struct Xorshift {
  uint32_t seed;
  uint32_t operator()(uint32_t n) {
    seed ^= seed << 13;
    seed ^= seed >> 17;
    seed ^= seed << 5;
    return seed % n;
  }
};

const MotionModel kMachine{{150000, 100000}, {3000000, 2000000}, 2000, 1500, {0, 0}, {80000, 80000}};

JobHeader smallJob(uint16_t cols, uint16_t rows) {
  JobHeader h{};
  h.cols = cols;
  h.rows = rows;
  h.pitchUm[0] = h.pitchUm[1] = 50;
  h.originUm[0] = 1000;
  h.originUm[1] = 2000;
  h.map = DoseMap::Linear;
  h.fullUs = 2000;
  for (int k = 0; k < 4; k++) {
    h.gainPermille[k] = 1000;
    h.offsets[k][1] = static_cast<int16_t>(k);
  }
  return h;
}

// The current pass's events: each LED's intervals, then the jumps, as lists of numbers.
struct PassEvents {
  std::vector<std::vector<uint32_t>> leds[4];
  std::vector<std::vector<uint32_t>> jumps;
};

PassEvents eventsOf(ScanPlanner& planner) {
  PassEvents out;
  ScanEvent e;
  while (planner.next(e)) {
    if (e.jump) out.jumps.push_back({e.window, e.windows, e.flyUs});
    else out.leds[e.led].push_back({e.onUs, e.offUs});
  }
  return out;
}

using Lists = std::vector<std::vector<uint32_t>>;

}  // namespace

TEST(ScanGolden, ReproducesItsOwnScans) { checkScanGolden("scan-cpp.json"); }

TEST(ScanPlanner, CentresGrayCellsMergesFullRunsAndReversesTheSecondPass) {
  JobHeader h = smallJob(12, 8);
  std::vector<std::vector<uint8_t>> rows(8, std::vector<uint8_t>(12, 0));
  rows[0][2] = rows[0][3] = rows[0][5] = 255;
  rows[0][4] = 128;  // t = 1004 µs, 498 µs into its window
  rows[4][3] = 51;   // t = 400 µs
  rows[4][10] = 255;
  GridCells cells(rows);
  ScanPlanner planner(h, cells, kMachine);
  EXPECT_EQ(planner.motion().windowUs, 2000u);
  EXPECT_EQ(planner.motion().speedUmS, 25000u);
  EXPECT_EQ(planner.motion().accelUs, 8334u);
  EXPECT_EQ(planner.motion().overscanUm, 105u);
  ScanPass p;
  ASSERT_TRUE(planner.nextPass(p));
  EXPECT_FALSE(p.descending);
  EXPECT_EQ(p.first, 2);
  EXPECT_EQ(p.last, 5);
  EXPECT_EQ(p.runUpUm, 1000 + 100 - 25 - 105);
  PassEvents a = eventsOf(planner);
  EXPECT_EQ(a.leds[0], (Lists{{0, 4000}, {4498, 5502}, {6000, 8000}}));
  EXPECT_EQ(a.jumps, Lists{});
  ASSERT_TRUE(planner.nextPass(p));
  EXPECT_TRUE(p.descending);
  EXPECT_EQ(p.hy, 4);
  EXPECT_EQ(p.first, 3);
  EXPECT_EQ(p.last, 10);
  EXPECT_EQ(p.runUpUm, 1000 + 500 + 25 + 105);
  // Six blank windows flown in F(6) = 2 × isqrt(510e12 / 3e6) − 2 × 8334 = 9408 µs, not 12000: it
  // saves more than a window.
  PassEvents b = eventsOf(planner);
  EXPECT_EQ(b.jumps, (Lists{{1, 6, 9408}}));
  EXPECT_EQ(b.leds[0], (Lists{{0, 2000}, {2000 + 9408 + 800, 2000 + 9408 + 1200}}));
  EXPECT_FALSE(planner.nextPass(p));
}

TEST(ScanPlanner, NegativeOffsetsAndTheSpeedCap) {
  JobHeader h = smallJob(12, 4);
  const int16_t dx[4] = {0, -3, 4, -1};
  for (int k = 0; k < 4; k++) h.offsets[k][0] = dx[k];
  std::vector<std::vector<uint8_t>> rows(4, std::vector<uint8_t>(12, 0));
  for (auto& r : rows) r[5] = 255;
  GridCells cells(rows);
  ScanPlanner planner(h, cells, kMachine);
  ScanPass p;
  ASSERT_TRUE(planner.nextPass(p));
  EXPECT_EQ(p.first, 1);
  EXPECT_EQ(p.last, 8);
  // Lit in windows 0, 4, 5 and 7: F(3) = 5240 and F(1) = 1950 µs beat 6000 and 2000, but by less
  // than a window, so neither stretch is flown.
  PassEvents e = eventsOf(planner);
  EXPECT_EQ(e.jumps, Lists{});
  const uint32_t on[4] = {8000, 14000, 0, 10000};
  for (uint8_t k = 0; k < 4; k++) EXPECT_EQ(e.leds[k], (Lists{{on[k], on[k] + 2000}})) << "LED " << int(k);

  MotionModel slow = kMachine;
  slow.vmaxUmS[0] = 10000;  // 5000 µs windows: full cells no longer touch
  std::vector<std::vector<uint8_t>> run(4, std::vector<uint8_t>(12, 0));
  run[0][2] = run[0][3] = 255;
  GridCells runCells(run);
  const JobHeader plain = smallJob(12, 4);  // the planner keeps a reference: it must outlive it
  ScanPlanner capped(plain, runCells, slow);
  EXPECT_EQ(capped.motion().windowUs, 5000u);
  EXPECT_EQ(capped.motion().speedUmS, 10000u);
  ASSERT_TRUE(capped.nextPass(p));
  EXPECT_EQ(eventsOf(capped).leds[0], (Lists{{1500, 3500}, {6500, 8500}}));
}

// A window the Mega's step engine cannot run (planner.md "Limits"): no pass, and refused() says why,
// so the Mega answers M29 with E29. 200 ms at 50 µm and 80 steps/mm is 50 ms a step; 131 ms runs.
TEST(ScanPlanner, RefusesAWindowTheStepEngineCannotRun) {
  std::vector<std::vector<uint8_t>> rows(4, std::vector<uint8_t>(12, 255));
  for (uint32_t fullUs : {200000u, 131000u}) {
    JobHeader h = smallJob(12, 4);
    h.fullUs = fullUs;
    GridCells cells(rows);
    ScanPlanner planner(h, cells, kMachine);
    ScanPass p;
    EXPECT_TRUE(planner.supported());
    EXPECT_EQ(planner.nextPass(p), fullUs < 131072);
    EXPECT_EQ(planner.refused(), fullUs >= 131072);
  }
}

// More stretches than a pass flies: the kMaxJumps longest, the lower column first among equals, in
// both directions; jump() lists them as next() hands them out, and the estimate counts only them.
TEST(ScanPlanner, FliesOnlyTheLongestStretches) {
  const uint16_t gaps[11] = {10, 20, 12, 30, 12, 40, 9, 50, 12, 15, 12};
  JobHeader h = smallJob(240, 8);
  std::vector<std::vector<uint8_t>> rows(8, std::vector<uint8_t>(240, 0));
  std::vector<uint32_t> lows;  // each stretch's lowest column
  uint32_t c = 2;
  rows[0][c] = rows[4][c] = 255;
  for (uint16_t g : gaps) {
    lows.push_back(c + 1);
    c += g + 1u;
    rows[0][c] = rows[4][c] = 255;
  }
  // Kept: 50, 40, 30, 20, 15 and the three 12s of lower columns; not the last 12, nor 10 or 9.
  std::set<std::pair<uint32_t, uint32_t>> kept;
  for (uint8_t i : {1, 2, 3, 4, 5, 7, 8, 9}) kept.insert({lows[i], gaps[i]});
  GridCells cells(rows);
  ScanPlanner planner(h, cells, kMachine);
  ScanPass p;
  for (int pass = 0; pass < 2; pass++) {
    const uint64_t before = planner.estimateUs();
    ASSERT_TRUE(planner.nextPass(p));
    EXPECT_EQ(p.descending, pass == 1);
    ASSERT_EQ(planner.jumps(), kMaxJumps);
    std::vector<std::vector<uint32_t>> listed;
    for (uint8_t i = 0; i < planner.jumps(); i++) {
      uint32_t window, windows, us;
      planner.jump(i, window, windows, us);
      listed.push_back({window, windows, us});
    }
    PassEvents e = eventsOf(planner);
    EXPECT_EQ(e.jumps, listed);
    std::set<std::pair<uint32_t, uint32_t>> flown;
    uint64_t saved = 0;
    for (const auto& j : e.jumps) {
      const uint32_t low = p.descending ? static_cast<uint32_t>(p.last) - j[0] - j[1] + 1 : static_cast<uint32_t>(p.first) + j[0];
      flown.insert({low, j[1]});
      saved += j[1] * 2000ull - j[2];
    }
    EXPECT_EQ(flown, kept) << "pass " << pass;
    // Full cells: the last one ends with its window, S(n − 1) + W, which the estimate adds.
    const uint64_t span = static_cast<uint64_t>(p.last - p.first + 1) * 2000 - saved;
    EXPECT_EQ(e.leds[0].back()[1], span);
    EXPECT_GT(planner.estimateUs() - before, span + 2 * planner.motion().accelUs);
  }
}

TEST(ScanPlanner, PlansAPassAtATimeWithoutTheHeap) {
  std::vector<std::vector<uint8_t>> rows(64, std::vector<uint8_t>(4096, 0));
  for (size_t y = 0; y < rows.size(); y++)
    for (size_t x = y % 7; x < 4096; x += 3) rows[y][x] = static_cast<uint8_t>(1 + (x * y) % 255);
  JobHeader h = smallJob(4096, 64);
  GridCells cells(rows);
  const long before = allocations;
  ScanPlanner planner(h, cells, kMachine);
  ScanPass p;
  int passes = 0, slowed = 0;
  while (planner.nextPass(p)) {
    ScanEvent e;
    while (planner.next(e)) {
    }
    passes++;
    if (planner.passMotion().windowUs > planner.motion().windowUs) slowed++;
  }
  EXPECT_EQ(allocations - before, 0) << "the scan planner allocated";
  EXPECT_EQ(passes, 16);
  // Each LED's row is read three times: for the pass's extent and time, for its program lines'
  // load on the link, then for its events; twice more each time the link cap slows the pass.
  EXPECT_GE(cells.rowsOpened, 3 * 64);
  EXPECT_EQ((cells.rowsOpened - 3 * 64) % 8, 0);
  EXPECT_EQ(cells.rowsOpened > 3 * 64, slowed > 0);
  std::printf("[scan memory] rows opened: %ld for 64 rows, %d of %d passes slowed for the link\n", static_cast<long>(cells.rowsOpened), slowed, passes);
  std::printf("[scan memory] sizeof(ScanPlanner) = %zu bytes without the host's duration table\n", sizeof(ScanPlanner) - Durations::kTableBytes);
}

TEST(ScanPlanner, EveryLitCellItsDoseOnceWithLedsSpreadOverManyRows) {
  // As the stop planner's property test: rows taken live in a ring of kCoveredWindowRows, jobs are
  // taller than it, and every lit cell still gets exactly its t_k(v) once, read back from the events.
  Xorshift rnd{4242};
  for (int trial = 0; trial < 16; trial++) {
    const uint16_t rows = static_cast<uint16_t>(1200 + rnd(1500)), cols = static_cast<uint16_t>(3 + rnd(30));
    std::vector<std::vector<uint8_t>> grid(rows, std::vector<uint8_t>(cols, 0));
    for (auto& row : grid)
      for (auto& v : row)
        if (rnd(3) == 0) v = static_cast<uint8_t>(1 + rnd(255));
    JobHeader h = smallJob(cols, rows);
    h.fullUs = 500 + rnd(3000);
    const uint16_t spread = trial % 3 == 0 ? static_cast<uint16_t>(kCoveredWindowRows - 1) : static_cast<uint16_t>(rnd(kCoveredWindowRows));
    for (int k = 0; k < 4; k++) {
      h.gainPermille[k] = static_cast<uint16_t>(800 + rnd(400));
      h.offsets[k][0] = static_cast<int16_t>(rnd(7)) - 3;
      h.offsets[k][1] = static_cast<int16_t>(k == 3 ? spread : rnd(spread + 1u));
    }
    GridCells cells(grid);
    ScanPlanner planner(h, cells, kMachine);
    ASSERT_TRUE(planner.supported());
    const Durations dose(h);
    const uint32_t w = planner.motion().windowUs;
    std::vector<std::vector<int64_t>> got(rows, std::vector<int64_t>(cols, 0));
    ScanPass p;
    while (planner.nextPass(p)) {
      PassEvents e = eventsOf(planner);
      // Window starts S(j), with the jumps' windows skipped.
      const uint32_t n = static_cast<uint32_t>(p.last - p.first + 1);
      std::vector<int64_t> s(n, -1);
      size_t next = 0;
      for (uint32_t j = 0, t = 0; j < n; j++) {
        if (next < e.jumps.size() && e.jumps[next][0] == j) {
          t += e.jumps[next][2];
          j += e.jumps[next][1] - 1;
          next++;
          continue;
        }
        s[j] = t;
        t += w;
      }
      ASSERT_EQ(next, e.jumps.size()) << "trial " << trial;
      for (uint8_t k = 0; k < 4; k++) {
        for (const auto& iv : e.leds[k]) {
          for (uint32_t j = 0; j < n; j++) {
            if (s[j] < 0) continue;
            const int64_t lo = std::max<int64_t>(iv[0], s[j]), hi = std::min<int64_t>(iv[1], s[j] + w);
            if (hi <= lo) continue;
            const int32_t hx = p.descending ? p.last - static_cast<int32_t>(j) : p.first + static_cast<int32_t>(j);
            const int32_t r = p.hy + h.offsets[k][1], c = hx + h.offsets[k][0];
            ASSERT_TRUE(r >= 0 && r < rows && c >= 0 && c < cols) << "trial " << trial;
            ASSERT_EQ(got[r][c], 0) << "trial " << trial << ": cell " << r << "," << c << " exposed twice";
            got[r][c] = (hi - lo) * 8 + k;  // its time, and which LED
          }
        }
      }
    }
    // The LED that exposes each row: the stop planner's, which this shares the pass rules with.
    std::vector<int> led(rows, -1);
    Planner stops(h, cells, kMachine);
    Stop st;
    while (stops.next(st))
      for (int k = 0; k < 4; k++)
        if (st.us[k]) led[st.hy + h.offsets[k][1]] = k;
    for (int r = 0; r < rows; r++)
      for (int c = 0; c < cols; c++) {
        const int k = led[r];
        const int64_t want = k >= 0 && dose.us(static_cast<uint8_t>(k), grid[r][c]) ? dose.us(static_cast<uint8_t>(k), grid[r][c]) * 8 + k : 0;
        ASSERT_EQ(got[r][c], want) << "trial " << trial << " cell " << r << "," << c;
      }
  }
}

// The pass as the Nano runs it: one event per switching moment, touching full cells one stretch.
TEST(ScanPlanner, GivesThePassAsTheNanosEvents) {
  JobHeader h = smallJob(10, 4);
  std::vector<std::vector<uint8_t>> rows(4, std::vector<uint8_t>(10, 0));
  rows[0][2] = rows[0][3] = rows[0][5] = 255;
  rows[0][4] = 128;
  rows[1][2] = rows[1][3] = 51;
  GridCells cells(rows);
  ScanPlanner planner(h, cells, kMachine);
  ScanPass p;
  ASSERT_TRUE(planner.nextPass(p));
  std::vector<std::pair<uint32_t, uint8_t>> events;
  uint32_t t;
  uint8_t m;
  while (planner.nextEvent(t, m)) events.push_back({t, m});
  EXPECT_EQ(events, (std::vector<std::pair<uint32_t, uint8_t>>{
                        {0, 1}, {800, 3}, {1200, 1}, {2800, 3}, {3200, 1}, {4000, 0}, {4498, 1}, {5502, 0}, {6000, 1}, {8000, 0}}));
}

// Stream mode: rows arriving a few at a time give the very passes and events of the whole job, and
// no pass opens before the rows it reads are there.
TEST(ScanPlanner, PlansTheSamePassesWhileRowsArrive) {
  Xorshift rnd{77};
  const uint16_t rows = 90, cols = 40;
  std::vector<std::vector<uint8_t>> grid(rows, std::vector<uint8_t>(cols, 0));
  for (auto& row : grid)
    for (auto& v : row)
      if (rnd(4) == 0) v = static_cast<uint8_t>(1 + rnd(255));
  JobHeader h = smallJob(cols, rows);
  for (int k = 0; k < 4; k++) h.offsets[k][1] = static_cast<int16_t>(k * 3);
  using Pass = std::vector<std::pair<uint32_t, uint8_t>>;
  auto plan = [&](bool streamed) {
    GridCells cells(grid);
    ScanPlanner planner(h, cells, kMachine);
    std::vector<Pass> out;
    uint16_t known = 0;
    if (streamed) planner.setKnownRows(known);
    ScanPass p;
    for (;;) {
      if (!planner.nextPass(p)) {
        if (!planner.starved()) break;
        EXPECT_LT(known, rows);
        known = static_cast<uint16_t>(known + 1 + rnd(5));
        if (known > rows) known = rows;
        planner.setKnownRows(known);
        continue;
      }
      if (streamed) {
        EXPECT_TRUE(known == rows || p.hy + 9 < known) << "a pass read a row not yet arrived";
        EXPECT_LE(planner.lowestRowNeeded(), p.hy + 0);
      }
      Pass e;
      uint32_t t;
      uint8_t m;
      while (planner.nextEvent(t, m)) e.push_back({t, m});
      out.push_back(e);
    }
    return out;
  };
  const std::vector<Pass> whole = plan(false), streamed = plan(true);
  EXPECT_GT(whole.size(), 10u);
  EXPECT_EQ(streamed, whole);
}

// A machine that cannot fly: the same light at the same places, every window W after the last.
TEST(ScanPlanner, NeverFlyCrossesBlankStretchesAtTheSpeed) {
  const uint16_t cols = 200;
  std::vector<std::vector<uint8_t>> rows(4, std::vector<uint8_t>(cols, 0));
  for (uint16_t c : {3, 4, 60, 61, 62, 150, 199}) rows[0][c] = 200;
  JobHeader h = smallJob(cols, 4);  // 2 ms at 50 µm: 25 mm/s, a quarter of the top speed
  GridCells flyCells(rows), slowCells(rows);
  ScanPlanner flying(h, flyCells, kMachine), slow(h, slowCells, kMachine);
  ASSERT_TRUE(flying.mayFly());
  slow.neverFly();
  EXPECT_FALSE(slow.mayFly());
  ScanPass a, b;
  ASSERT_TRUE(flying.nextPass(a));
  ASSERT_TRUE(slow.nextPass(b));
  std::vector<std::pair<uint32_t, uint8_t>> fe, se;
  uint32_t t;
  uint8_t m;
  while (flying.nextEvent(t, m)) fe.push_back({t, m});
  while (slow.nextEvent(t, m)) se.push_back({t, m});
  ASSERT_EQ(fe.size(), se.size());
  const uint32_t w = slow.motion().windowUs, on = Durations(h).us(0, 200), lead = (w - on) / 2;
  for (const auto& e : se) {
    // Each edge sits in the window of its column at the constant speed: j·W plus its offset.
    const uint32_t j = e.first / w;
    EXPECT_TRUE(e.first % w == lead || e.first % w == lead + on) << e.first;
    EXPECT_TRUE(j <= 199u);
  }
  EXPECT_LT(fe.back().first, se.back().first);  // flying is quicker
  EXPECT_EQ(se.back().first, 196 * w + lead + on);  // column 199, window 196
  EXPECT_GT(slow.estimateUs(), flying.estimateUs());
}
